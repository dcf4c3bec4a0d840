#pragma once
// Force kernels of docs/model.md section 4: small stateless functions on fixed-size Eigen types.
// Each term gives its energy, its force and the Jacobian blocks that implicit solvers need. The
// gather/scatter over particles is in core/model/cloth_system.cpp.
//
// The spring force that runs in every step is spring_force() below evaluated stencil by stencil
// over the grid in packets: spring_kernel_impl.hpp beside this file (called from
// grid_spring_forces.cpp); tests/core/forces/test_grid_spring_forces.cpp checks the two agree.
//
// Convention: for a pair (i, j), d = x_j - x_i, L = |d|, u = d / L. A kernel returns the force on
// i; j feels the opposite. The Jacobian blocks are J = dF_i/dx_j = -dF_i/dx_i (and the same for
// velocities), so a pair contributes [-J J; J -J] to the rows and columns (i, j).
#include <cmath>

#include "core/state/state.hpp"

namespace drape {

/// Below this length a spring has no defined direction: its force and Jacobian are zero.
inline constexpr double degenerate_length = 1e-12;

/// Elastic spring energy k (L - L0)^2 / 2.
inline double spring_energy(const Vec3& d, double k, double rest) {
  const double stretch = d.norm() - rest;
  return 0.5 * k * stretch * stretch;
}

/// Elastic spring force on i: k (L - L0) u.
inline Vec3 spring_force(const Vec3& d, double k, double rest) {
  const double length = d.norm();
  if (length < degenerate_length) return Vec3::Zero();
  return (k * (length - rest) / length) * d;
}

/// dF_i/dx_j of the elastic spring: k [u u^T + (1 - L0/L)(I - u u^T)]. With `definite`, the
/// transverse term is clamped at 0 for compressed springs (Choi and Ko 2002), which keeps the
/// stiffness matrix negative semi-definite for conjugate gradients and preconditioners.
inline Mat3 spring_jacobian(const Vec3& d, double k, double rest, bool definite) {
  const double length = d.norm();
  if (length < degenerate_length) return Mat3::Zero();
  const Vec3 u = d / length;
  double transverse = 1.0 - rest / length;
  if (definite && transverse < 0.0) transverse = 0.0;
  const Mat3 uu = u * u.transpose();
  return k * (uu + transverse * (Mat3::Identity() - uu));
}

/// Spring damping force on i: c ((v_j - v_i) . u) u, with w = v_j - v_i.
inline Vec3 damping_force(const Vec3& d, const Vec3& w, double c) {
  const double length = d.norm();
  if (length < degenerate_length) return Vec3::Zero();
  const Vec3 u = d / length;
  return (c * w.dot(u)) * u;
}

/// dF_i/dv_j of the spring damping: c u u^T.
inline Mat3 damping_velocity_jacobian(const Vec3& d, double c) {
  const double length = d.norm();
  if (length < degenerate_length) return Mat3::Zero();
  const Vec3 u = d / length;
  return c * u * u.transpose();
}

/// dF_i/dx_j of the spring damping (the direction u turns with d):
/// c / L [u w^T P + (w . u) P], with P = I - u u^T.
inline Mat3 damping_position_jacobian(const Vec3& d, const Vec3& w, double c) {
  const double length = d.norm();
  if (length < degenerate_length) return Mat3::Zero();
  const Vec3 u = d / length;
  const Mat3 projector = Mat3::Identity() - u * u.transpose();
  return (c / length) * (u * (projector * w).transpose() + w.dot(u) * projector);
}

// Collision (paper section 2.3, docs/model.md section 4 model `particle`): a compression-only spring of rest
// length delta between the cloth particle and its nearest object particle, which does not move.
// With d = x - p_o the force on the cloth particle is k (delta - |d|) d / |d|.

/// Collision energy k (delta - |d|)^2 / 2 for |d| < delta, else 0.
inline double collision_energy(const Vec3& d, double k, double delta) {
  const double gap = delta - d.norm();
  return gap > 0.0 ? 0.5 * k * gap * gap : 0.0;
}

/// Repulsive force on the cloth particle, with length = |d| already known (the contact query
/// measures it); along `normal` when |d| is nearly 0.
inline Vec3 collision_force(const Vec3& d, double length, const Vec3& normal, double k,
                            double delta) {
  if (length >= delta) return Vec3::Zero();
  if (length < degenerate_length) return k * delta * normal;
  return (k * (delta - length) / length) * d;
}

/// Repulsive force on the cloth particle; along `normal` when |d| is nearly 0.
inline Vec3 collision_force(const Vec3& d, const Vec3& normal, double k, double delta) {
  return collision_force(d, d.norm(), normal, k, delta);
}

/// dF/dx of the collision force (the elastic spring Jacobian with L0 = delta, sign flipped
/// because d points from the object to the cloth).
inline Mat3 collision_jacobian(const Vec3& d, double k, double delta, bool definite) {
  if (d.norm() >= delta) return Mat3::Zero();
  return -spring_jacobian(d, k, delta, definite);
}

}  // namespace drape
