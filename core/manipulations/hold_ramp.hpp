#pragma once
// The soft hold (docs/manipulations.md, "Soft hold"): instead of snapping onto the hand, a newly
// held particle blends from the path it was on to the hand's trajectory over `hold_ramp` seconds.
#include <memory>

#include "core/model/constraints.hpp"

namespace drape {

/// p(t) = (1 - s) (x0 + v0 (t - t0)) + s q(t), s = 3 tau^2 - 2 tau^3, tau = (t - t0) / T in
/// [0, 1]: p(t0) = x0, p'(t0) = v0, and from t0 + T on p = q (position and velocity both
/// continuous, so the hold injects no jump into the cloth).
class RampedTrajectory final : public Trajectory {
 public:
  /// `target` is the hand's trajectory q; x0, v0 the particle's state at the hold time t0.
  RampedTrajectory(std::shared_ptr<const Trajectory> target, const Vec3& x0, const Vec3& v0,
                   double t0, double duration);
  Vec3 position(double t) const override;
  Vec3 velocity(double t) const override;
  Vec3 acceleration(double t) const override;

 private:
  double tau(double t) const;

  std::shared_ptr<const Trajectory> m_target;
  Vec3 m_x0, m_v0;
  double m_t0, m_duration;
};

}  // namespace drape
