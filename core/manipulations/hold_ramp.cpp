#include "core/manipulations/hold_ramp.hpp"

#include <algorithm>

namespace drape {

RampedTrajectory::RampedTrajectory(std::shared_ptr<const Trajectory> target, const Vec3& x0,
                                   const Vec3& v0, double t0, double duration)
    : m_target(std::move(target)), m_x0(x0), m_v0(v0), m_t0(t0), m_duration(duration) {}

double RampedTrajectory::tau(double t) const {
  return std::clamp((t - m_t0) / m_duration, 0.0, 1.0);
}

Vec3 RampedTrajectory::position(double t) const {
  const double u = tau(t);
  if (u >= 1.0) return m_target->position(t);
  const double s = u * u * (3.0 - 2.0 * u);
  const Vec3 free = m_x0 + m_v0 * (t - m_t0);
  return (1.0 - s) * free + s * m_target->position(t);
}

Vec3 RampedTrajectory::velocity(double t) const {
  const double u = tau(t);
  if (u >= 1.0) return m_target->velocity(t);
  const double s = u * u * (3.0 - 2.0 * u);
  const double ds = 6.0 * u * (1.0 - u) / m_duration;
  const Vec3 gap = m_target->position(t) - (m_x0 + m_v0 * (t - m_t0));
  return (1.0 - s) * m_v0 + s * m_target->velocity(t) + ds * gap;
}

Vec3 RampedTrajectory::acceleration(double t) const {
  const double u = tau(t);
  if (u >= 1.0) return m_target->acceleration(t);
  const double s = u * u * (3.0 - 2.0 * u);
  const double ds = 6.0 * u * (1.0 - u) / m_duration;
  const double dds = (6.0 - 12.0 * u) / (m_duration * m_duration);
  const Vec3 gap = m_target->position(t) - (m_x0 + m_v0 * (t - m_t0));
  const Vec3 gap_rate = m_target->velocity(t) - m_v0;
  return s * m_target->acceleration(t) + 2.0 * ds * gap_rate + dds * gap;
}

}  // namespace drape
