#pragma once
// The `smooth` model's contact potential on a gap G (docs/model.md section 4.11):
//   E(G) = k / (3 delta) (delta - G)^3 for G < delta, 0 beyond,
// C2 at G = delta (value, slope and curvature vanish there), finite for any G (a penetrated
// particle is pushed out, never met with an infinite barrier). At G = 0 its force k delta
// |grad G| is the `particle` model's at contact, and its stiffness 2 k.
#include <Eigen/Eigenvalues>

#include "core/model/state.hpp"

namespace drape {

/// E(G).
inline double smooth_contact_energy(double gap, double stiffness, double threshold) {
  if (gap >= threshold) return 0.0;
  const double d = threshold - gap;
  return stiffness / (3.0 * threshold) * d * d * d;
}

/// dE/dG (<= 0).
inline double smooth_contact_slope(double gap, double stiffness, double threshold) {
  if (gap >= threshold) return 0.0;
  const double d = threshold - gap;
  return -stiffness / threshold * d * d;
}

/// d2E/dG2 (>= 0).
inline double smooth_contact_curvature(double gap, double stiffness, double threshold) {
  return gap >= threshold ? 0.0 : 2.0 * stiffness * (threshold - gap) / threshold;
}

/// The symmetric 3x3 matrix with its negative eigenvalues set to 0 (the nearest positive
/// semi-definite matrix, as ipc-toolkit projects its barrier Hessians).
inline Mat3 project_to_psd(const Mat3& a) {
  Eigen::SelfAdjointEigenSolver<Mat3> eig;
  eig.computeDirect(a);
  return eig.eigenvectors() * eig.eigenvalues().cwiseMax(0.0).asDiagonal() *
         eig.eigenvectors().transpose();
}

}  // namespace drape
