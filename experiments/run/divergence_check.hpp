#pragma once
// Ends runs whose state no motion of the scene could reach (docs/outputs.md, summary.json).
#include <Eigen/Core>
#include <string>

#include "core/model/cloth_system.hpp"

namespace drape {

/// Bound on any particle's speed: a free fall over the whole run, plus twice the fastest
/// prescribed motion, plus the speed one particle would have if it alone took all the kinetic
/// and elastic energy present at the start or right after an event (mapping, attach). A
/// physical motion stays below it; a numerical blow-up far beyond the stability limit passes it
/// within a few steps, while one slightly beyond it can saturate below it (docs/outputs.md: the
/// energy rise is what shows those).
class DivergenceCheck {
 public:
  /// `horizon`: the time a free fall may last, the run's duration (or a live run's, in its replay).
  DivergenceCheck(double gravity, double horizon) : m_base(10.0 + 2.0 * gravity * horizon) {}

  /// Raises the bound by the energy stored in a state (call at the start and after events).
  void account_for(const ClothSystem& system, const EnergyBreakdown& e);
  /// An empty string when the state is sound (finite, below the bound), else the reason.
  std::string reason(const ClothSystem& system, double t, const Eigen::VectorXd& y) const;

 private:
  double m_base;
  double m_stored_speed = 0.0;
};

/// The energy terms of a state y = [x; v].
EnergyBreakdown energy_of(const ClothSystem& system, const Eigen::VectorXd& y);

}  // namespace drape
