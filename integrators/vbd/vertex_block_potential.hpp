#pragma once
// Backward Euler's incremental potential in positions, particle by particle, for Vertex Block
// Descent (Chen, Liu, Yang and Yuksel 2024, "Vertex Block Descent", ACM TOG 43(4), sections
// 3.1-3.3). With y = x_n + h v_n and v = (x - x_n) / h,
//     G(x) = 1/(2 h^2) |x - y|_M^2 + U(x) + h R_u(v),
// U the spring, gravity and collision energy (with the lagged friction potential of docs/model.md
// section 4.12 while the system holds one frozen) and R_u the Rayleigh dissipation of air damping
// (c_air |v|^2 / 2) and spring damping (c_s ((v_j - v_i) . u)^2 / 2) with the springs'
// directions u frozen (freeze_directions). It is the IncrementalPotential of converged backward
// Euler (integrators/newton/incremental_potential.hpp) written in x instead of v: E_k(v) =
// G(x_n + h v), so both have the same minimiser, and grad_x G = F(x, v) - M (x - y) / h^2
// there. G restricted to one particle i (the others held) is a function of x_i alone whose
// gradient and Hessian need only i's incident springs and its own collision term: the block
// that VBD minimises by one 3x3 Newton step.
#include <Eigen/Core>
#include <vector>

#include "core/model/cloth_system.hpp"

namespace drape {

/// -grad_i G and the block of G's Hessian on particle i.
struct VertexBlock {
  Vec3 force = Vec3::Zero();
  Mat3 hessian = Mat3::Zero();
};

/// G of one backward-Euler step, evaluated per particle from flat incident-spring arrays.
class VertexBlockPotential {
 public:
  explicit VertexBlockPotential(const ClothSystem& system);

  /// Starts a step of size h from positions x_n and velocities v_n (3N each), gravity a_ext.
  void begin_step(double h, ConstVecRef x_n, ConstVecRef v_n);
  /// Freezes the spring damping directions u at the positions x (a no-op without spring
  /// damping): each iterate's G is then a function of x alone, as E_k is for Newton.
  void freeze_directions(ConstVecRef x);

  /// -grad_i G and the Hessian block at x (3N). `definite` clamps compressed springs'
  /// transverse stiffness (forces.hpp) and projects the collision Hessian to positive
  /// semi-definite, so that the block is at least M / h^2: positive definite.
  VertexBlock block(int i, const double* x, bool definite) const;
  /// G(x with x_i moved by dx) - G(x), written as differences of each term so that it keeps
  /// its relative accuracy when the move is small (no cancellation of G's large terms); in
  /// `magnitude` the sum of the terms' absolute values, which bounds its round-off.
  double energy_change(int i, const double* x, const Vec3& dx, double& magnitude) const;
  /// G(x) over the free particles' terms and all springs (the fixed particles' own terms are
  /// constants of the step); in `magnitude` the sum of its terms' absolute values.
  double value(ConstVecRef x, double& magnitude) const;
  double value(ConstVecRef x) const;

  double step_size() const { return m_h; }
  /// y = x_n + h v_n (3N).
  const Eigen::VectorXd& inertia_target() const { return m_y; }
  const Eigen::VectorXd& start_positions() const { return m_x_n; }

 private:
  const ClothSystem& m_system;
  double m_h = 0.0;
  double m_mass = 0.0, m_c_spring = 0.0, m_c_air = 0.0;
  Vec3 m_weight = Vec3::Zero();  // m g
  // Incident springs of particle i: entries m_offsets[i] .. m_offsets[i+1] of the arrays below
  // (CSR), each with the spring, the other particle, its stiffness and rest length.
  std::vector<int> m_offsets, m_spring, m_other;
  std::vector<double> m_stiffness, m_rest;
  std::vector<Vec3> m_directions;  // per spring, frozen u (zero when degenerate)
  Eigen::VectorXd m_x_n, m_y;
};

}  // namespace drape
