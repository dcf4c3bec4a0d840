#pragma once
// The stability limit of the explicit steps (leap-frog, symplectic Euler) on a cloth linearised
// at a state: the fastest mode's frequency and damping rate, and the largest step h with
// h^2 omega^2 + 2 h c < 4 (docs/model.md, "Stability limit"). Exact where the damping is
// proportional to the stiffness (one spring constant, at rest); an estimate elsewhere.
#include "core/model/cloth_system.hpp"

namespace drape {

struct ExplicitStabilityLimit {
  double omega = 0.0;         ///< the largest sqrt(eigenvalue) of -M^-1 dF/dx on the free particles [rad/s]
  double damping_rate = 0.0;  ///< that mode's c = -u' M^-1 dF/dv u, u its unit vector [1/s]
  double undamped = 0.0;      ///< 2 / omega [s]
  double damped = 0.0;        ///< the largest h with h^2 omega^2 + 2 h c < 4 [s]
  int iterations = 0;         ///< power iterations until the Rayleigh quotient settled
};

/// The fastest mode of `system` linearised at (x, v), by power iteration on -M^-1 dF/dx (the
/// exact Jacobian; its fixed rows and columns dropped) until the Rayleigh quotient changes by
/// less than 1e-10 relative in an iteration (closer, round-off moves it: a 12 x 12 cloth's
/// quotient never settled to 1e-12), at most `max_iterations` (std::runtime_error beyond).
ExplicitStabilityLimit explicit_stability_limit(const ClothSystem& system, ConstVecRef x,
                                                ConstVecRef v, int max_iterations = 200000);

}  // namespace drape
