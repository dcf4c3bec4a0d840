#pragma once
// Which particle a hold takes: the free particle the hand came within the hold threshold of
// first inside the step, the cloth moving linearly over it (docs/model.md section 7, "Hold"), so
// that the particle does not depend on the step.
#include <Eigen/Core>
#include <limits>

#include "core/input/hand_track.hpp"
#include "core/model/cloth_system.hpp"

namespace drape {

/// The free (not fixed) particle of `system` nearest `p` in positions `y` (3N or more), with its
/// distance in `distance`; -1 if every particle is fixed.
int nearest_free_particle(const ClothSystem& system, const Vec3& p, const Eigen::VectorXd& y,
                          double& distance);

/// The hold search over a step: remembers the previous update's time and, while a hold may need
/// them, the cloth's positions then.
class HoldSearch {
 public:
  /// The free particle `hand` came within `threshold` of first over (previous update, t], the
  /// cloth moving linearly from the previous update's positions to `y`'s; -1 if none.
  int first_reached_particle(const ClothSystem& system, const HandTrack& track, Hand hand,
                             double t, const Eigen::VectorXd& y, double threshold) const;
  /// Ends the update at t with state `y`: keeps the cloth's positions for the next step's search
  /// when a hand `may_hold` in it.
  void finish_update(double t, const Eigen::VectorXd& y, Eigen::Index num_particles,
                     bool may_hold);

 private:
  /// Time of the previous update (the last step's start); NaN before the first.
  double m_previous_update = std::numeric_limits<double>::quiet_NaN();
  /// The cloth's positions at m_previous_update, kept only when a hold search may need them
  /// (empty otherwise: the search then takes the cloth at the step's end).
  Eigen::VectorXd m_previous_positions;
};

}  // namespace drape
