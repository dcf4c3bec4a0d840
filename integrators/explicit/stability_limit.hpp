#pragma once
// The stability limit of the explicit steps (leap-frog, symplectic Euler) on a cloth linearised
// at a state: the fastest mode's frequency and damping rate, and the largest step h with
// h^2 omega^2 + 2 h c < 4 (docs/model.md, "Stability limit"). Exact where the damping is
// proportional to the stiffness (one spring constant, at rest); an estimate elsewhere.
#include <functional>

#include "core/model/cloth_system.hpp"

namespace drape {

struct ExplicitStabilityLimit {
  double omega = 0.0;         ///< the largest sqrt(eigenvalue) of -M^-1 dF/dx on the free particles [rad/s]
  double damping_rate = 0.0;  ///< that mode's c = -u' M^-1 dF/dv u, u its unit vector [1/s]
  double undamped = 0.0;      ///< 2 / omega [s]
  double damped = 0.0;        ///< the largest h with h^2 omega^2 + 2 h c < 4 [s]
  /// The imaginary part of omega^2: 0 for a symmetric Jacobian; the paper's contact force (no
  /// potential's) can make the fastest mode's eigenvalue complex, and the bound an estimate.
  double omega2_imaginary = 0.0;
  int jacobian_products = 0;  ///< products with -M^-1 dF/dx the eigensolver took
};

/// The fastest mode of `system` linearised at (x, v): the eigenvalue of largest real part of
/// -M^-1 dF/dx (the exact Jacobian; its fixed rows and columns dropped) by Arnoldi's method with
/// implicit restarts (Spectra), to a relative residual of 1e-10, at most `max_restarts`
/// restarts (std::runtime_error beyond). `after_product`, when given, is called with the count
/// after every product (a large cloth takes minutes: the caller can say how far it is).
ExplicitStabilityLimit explicit_stability_limit(
    const ClothSystem& system, ConstVecRef x, ConstVecRef v, int max_restarts = 1000,
    const std::function<void(long products)>& after_product = {});

}  // namespace drape
