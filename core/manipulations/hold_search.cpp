#include "core/manipulations/hold_search.hpp"

#include <algorithm>
#include <cmath>

namespace drape {

namespace {

// A hold takes the particle the hand reached first, located inside the step to within
// hold_search_interval (docs/model.md section 7, "Hold"), so that the particle does not depend
// on the step: at 1/30 s the hand found at the step's end is up to 33 ms further on, nearer
// another particle, and the cloth has moved on too. Steps no longer than the interval test only
// their end.
constexpr double hold_search_interval = 1e-3;

}  // namespace

int nearest_free_particle(const ClothSystem& system, const Vec3& p, const Eigen::VectorXd& y,
                          double& distance) {
  const auto& fixed = system.constraints().mask();
  int best = -1;
  double best2 = std::numeric_limits<double>::infinity();
  for (int i = 0; i < system.num_particles(); ++i) {
    if (fixed[i]) continue;
    const double d2 = (y.segment<3>(3 * i) - p).squaredNorm();
    if (d2 < best2) best2 = d2, best = i;
  }
  distance = std::sqrt(best2);
  return best;
}

int HoldSearch::first_reached_particle(const ClothSystem& system, const HandTrack& track,
                                       Hand hand, double t, const Eigen::VectorXd& y,
                                       double threshold) const {
  const double t0 = m_previous_update;
  const int samples =
      std::isfinite(t0) && t > t0
          ? std::max(1, static_cast<int>(std::ceil((t - t0) / hold_search_interval - 1e-9)))
          : 1;
  // The cloth between the step's ends moves linearly (first-order dense output, as the hand
  // track's own interpolation between frames); without the start's positions, it is the end's.
  const Eigen::Index n3 = 3 * system.num_particles();
  const bool interpolate = samples > 1 && m_previous_positions.size() == n3;
  Eigen::VectorXd cloth = y.head(n3);
  for (int k = 1; k <= samples; ++k) {
    const double tk = k == samples ? t : t0 + (t - t0) * k / samples;
    const auto motion = track.motion(hand, tk);
    if (!motion || !motion->available) continue;
    if (interpolate) {
      const double s = static_cast<double>(k) / samples;
      cloth = (1.0 - s) * m_previous_positions + s * y.head(n3);
    }
    double distance = 0.0;
    const int candidate = nearest_free_particle(system, motion->position, cloth, distance);
    if (candidate >= 0 && distance < threshold) return candidate;
  }
  return -1;
}

void HoldSearch::finish_update(double t, const Eigen::VectorXd& y, Eigen::Index num_particles,
                               bool may_hold) {
  // The positions are needed only when a hand may hold in the next step and that step is longer
  // than the search interval (assumed as long as this one: fixed steps; the first step is
  // assumed long).
  const double last_step = t - m_previous_update;
  const bool long_steps = !std::isfinite(m_previous_update) || last_step > hold_search_interval;
  if (may_hold && long_steps)
    m_previous_positions = y.head(3 * num_particles);
  else
    m_previous_positions.resize(0);
  m_previous_update = t;
}

}  // namespace drape
