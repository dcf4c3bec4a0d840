#pragma once
// The incremental potential of one implicit stage of the cloth ODE
// (docs/integrators/line-search-newton.md, "Stages as minimisation"; Gast et al. 2015,
// "Optimization integrator for large time steps", IEEE TVCG 21(10)).
//
// An implicit Runge-Kutta stage solves z = a + gamma f_I(t, z), a the stage's known part (in
// ARKODE's correction form a = zpred + sdata). With z = [x; v] and f_I = [v; M^-1 F] on the
// free particles, x = a_x + gamma v eliminates the positions and the stage is g(v) = 0 with
//     g(v) = M (v - a_v) - gamma F(a_x + gamma v, v).
// F = -grad U(x) - grad_v R(v) for the elastic, collision and gravity energy U (and the lagged
// friction potential of docs/model.md section 4.12 while the system holds one frozen) and the Rayleigh
// dissipation R of air damping (c_air |v|^2 / 2) and spring damping (c ((v_j - v_i) . u)^2 / 2).
// With `with_smooth_friction`, R also has the smooth Coulomb force's dissipation
// mu lambda f0(|v_t|, epsilon_v) per particle (docs/friction.md), its contact force lambda n
// frozen at x_k likewise. The spring direction u turns with x, so R is frozen at the iterate
// x_k: then
//     E_k(v) = 1/2 (v - a_v)^T M (v - a_v) + U(a_x + gamma v) + gamma R_k(v)
// has grad E_k(v_k) = g(v_k) exactly, and its Hessian at v_k is S = M - gamma D - gamma^2 K
// with the definite K (ReducedNewtonSolver). Fixed particles take their stage values
// a + gamma f_I(t) (the prescribed rows of f_I do not depend on z) and are no unknowns.
#include <Eigen/Core>
#include <vector>

#include "core/model/cloth_system.hpp"

namespace drape {

/// E_k, its gradient g and the stage states of one implicit stage.
class IncrementalPotential {
 public:
  /// `split` selects the forces of f_I (all, or the springs for arkode-imex).
  IncrementalPotential(const ClothSystem& system, ForceSplit split);

  /// Starts a stage: z = a + gamma f_I(t, z) with known part `a` (6N). Sets the fixed rows of
  /// `z` (6N, the initial guess) to their stage values and the free positions to a_x + gamma v.
  void begin_stage(double t, double gamma, ConstVecRef a, VecRef z);
  /// Freezes the spring damping directions and, with the smooth friction, the contact forces
  /// at the positions of `z` (E_k of the docs).
  void freeze_damping(ConstVecRef z);
  /// z with free velocities v: x = a_x + gamma v on free particles, fixed rows unchanged.
  void state_of(ConstVecRef v, VecRef z) const;
  /// E_k at the state z (whose free positions follow its velocities).
  double value(ConstVecRef z) const;
  /// E_k at z, and in `magnitude` the sum of its terms' absolute values: E_k's round-off is
  /// about machine epsilon times that, whatever E_k itself.
  double value(ConstVecRef z, double& magnitude) const;
  /// g = M (v - a_v) - gamma F(x, v) on free particles, zero on fixed ones (3N).
  void gradient(ConstVecRef z, VecRef g) const;
  double gamma() const { return m_gamma; }
  double time() const { return m_t; }

 private:
  /// sum over free particles of mu lambda f0(|v_t|, epsilon_v), lambda n = m_contacts[i].
  double friction_dissipation(ConstVecRef v) const;

  const ClothSystem& m_system;
  ForceSplit m_split;
  double m_t = 0.0, m_gamma = 0.0;
  Eigen::VectorXd m_a, m_fixed_rhs;
  std::vector<Vec3> m_directions;  // spring e's unit direction u at x_k (zero if degenerate)
  std::vector<Vec3> m_contacts;    // particle i's contact force at x_k (smooth friction only)
  mutable Eigen::VectorXd m_force;
};

}  // namespace drape
