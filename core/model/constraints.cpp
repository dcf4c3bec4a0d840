#include "core/model/constraints.hpp"

#include <algorithm>

namespace drape {

ConstraintSet::ConstraintSet(int num_particles)
    : m_trajectory(num_particles), m_mask(num_particles, 0) {}

void ConstraintSet::fix(int i, std::shared_ptr<const Trajectory> trajectory) {
  if (!m_mask[i]) m_fixed.insert(std::upper_bound(m_fixed.begin(), m_fixed.end(), i), i);
  m_trajectory[i] = std::move(trajectory);
  m_mask[i] = 1;
}

void ConstraintSet::fix_at(int i, const Vec3& point) { fix(i, std::make_shared<FixedPoint>(point)); }

void ConstraintSet::release(int i) {
  if (!m_mask[i]) return;
  m_trajectory[i].reset();
  m_mask[i] = 0;
  m_fixed.erase(std::lower_bound(m_fixed.begin(), m_fixed.end(), i));
}

void ConstraintSet::apply_to_rhs(double t, VecRef x_dot, VecRef v_dot) const {
  for (const int i : m_fixed) {
    particle(x_dot, i) = m_trajectory[i]->velocity(t);
    particle(v_dot, i) = m_trajectory[i]->acceleration(t);
  }
}

void ConstraintSet::project(double t, VecRef x, VecRef v) const {
  for (const int i : m_fixed) {
    particle(x, i) = m_trajectory[i]->position(t);
    particle(v, i) = m_trajectory[i]->velocity(t);
  }
}

void ConstraintSet::zero_fixed(VecRef values) const {
  for (const int i : m_fixed) particle(values, i).setZero();
}

double ConstraintSet::max_speed(double t) const {
  double speed = 0.0;
  for (const int i : m_fixed) speed = std::max(speed, m_trajectory[i]->velocity(t).norm());
  return speed;
}

}  // namespace drape
