#pragma once
// The `smooth` model's contact potential on a gap G (docs/model.md section 4.11):
//   E(G) = k / (3 delta) (delta - G)^3                  for 0 <= G < delta, 0 beyond,
//   E(G) = k delta^2 / 3 - k delta G + k G^2            for G < 0 (its quadratic continuation),
// C2 at G = delta (value, slope and curvature vanish there) and at G = 0 (the continuation is
// the cubic's second-order Taylor polynomial there). Its curvature 2 k (delta - G) / delta rises
// from 0 at the threshold to 2 k at contact and stays 2 k inside: bounded, so an explicit step
// has a stability limit that a deep penetration cannot lower (the cubic alone grows without
// bound). At G = 0 its force k delta |grad G| is the `particle` model's at contact.
#include <Eigen/Eigenvalues>

#include "core/state/state.hpp"

namespace drape {

/// E(G).
inline double smooth_contact_energy(double gap, double stiffness, double threshold) {
  if (gap >= threshold) return 0.0;
  if (gap < 0.0) return stiffness * (threshold * threshold / 3.0 - threshold * gap + gap * gap);
  const double d = threshold - gap;
  return stiffness / (3.0 * threshold) * d * d * d;
}

/// dE/dG (<= 0).
inline double smooth_contact_slope(double gap, double stiffness, double threshold) {
  if (gap >= threshold) return 0.0;
  if (gap < 0.0) return -stiffness * (threshold - 2.0 * gap);
  const double d = threshold - gap;
  return -stiffness / threshold * d * d;
}

/// d2E/dG2, in [0, 2 k].
inline double smooth_contact_curvature(double gap, double stiffness, double threshold) {
  if (gap >= threshold) return 0.0;
  return gap < 0.0 ? 2.0 * stiffness : 2.0 * stiffness * (threshold - gap) / threshold;
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
