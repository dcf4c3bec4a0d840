#pragma once
// The two constraints of the xpbd integrator and XPBD's multiplier update, as small stateless
// functions: the spring's distance constraint and the contact constraint built from any
// collision model's energy (docs/integrators/xpbd.md).
#include <cmath>

#include "core/collision/collision.hpp"

namespace drape {

/// XPBD's multiplier increment with constraint damping (Macklin, Mueller and Chentanez 2016,
/// "XPBD", eq. 26): dlambda = (-C - a lambda - g grad C . (x - x_prev)) / ((1 + g) w + a), with
/// `weight` w = grad C M^-1 grad C^T, a = alpha / h^2 and g = alpha beta / h.
inline double xpbd_multiplier_step(double value, double weight, double compliance,
                                   double lambda, double damping, double gradient_motion) {
  return (-value - compliance * lambda - damping * gradient_motion) /
         ((1.0 + damping) * weight + compliance);
}

/// A contact constraint of one particle: value C >= 0 and gradient grad C.
struct ContactConstraint {
  double value = 0.0;
  Vec3 gradient = Vec3::Zero();
};

/// The collision energy U_i(x) >= 0 of cloth particle i written as C = sqrt(2 U / k) with
/// compliance 1/k, so that C^2 / (2 alpha) = U for every model, and
/// grad C = grad U / (k C) = -F / (k C). The particle model's U = k (delta - d)^2 / 2 gives
/// C = delta - d, grad C = -(x - p) / d. Returns false (no constraint) where U = 0; the force
/// is asked first because outside the threshold it is zero and the energy query is saved.
inline bool contact_constraint(const Collision& collision, int i, const Vec3& x,
                               ContactConstraint& out) {
  const Vec3 force = collision.force(i, x);
  if (force.isZero(0.0)) return false;
  const double k = collision.params().stiffness;
  const double energy = collision.energy(i, x);
  if (!(energy > 0.0)) return false;
  out.value = std::sqrt(2.0 * energy / k);
  out.gradient = force / (-k * out.value);
  return true;
}

}  // namespace drape
