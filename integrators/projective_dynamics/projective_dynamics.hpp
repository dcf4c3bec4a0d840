#pragma once
#include <optional>
#include <vector>

#include "integrators/interface/integrator.hpp"
#include "integrators/interface/integrator_declaration.hpp"
#include "integrators/interface/integrator_options.hpp"
#include "integrators/projective_dynamics/pd_global_matrix.hpp"

namespace drape {

/// Projective Dynamics for mass-spring cloth (Liu, Bargteil, O'Brien and Kavan 2013, "Fast
/// simulation of mass-spring systems", ACM TOG 32(6); Bouaziz et al. 2014, "Projective
/// Dynamics", ACM TOG 33(4)) in its quasi-Newton form (Liu, Bouaziz and Kavan 2017,
/// "Quasi-Newton methods for real-time simulation of hyperelastic materials", ACM TOG 36(3)):
/// backward Euler's step x_{n+1} minimises
///     E(x) = 1/(2h^2) |x - x_n - h v_n|_M^2 + U(x) + h R((x - x_n) / h)
/// (U: springs, gravity, collision; R: air and spring damping), and each of `iterations`
/// iterations takes x <- x + A^-1 (-grad E(x)) over the free particles, A the global matrix of
/// PdGlobalMatrix. For springs and inertia this is exactly the local/global iteration
/// (d_e = L0 (x_i - x_j)/|x_i - x_j|, then (M/h^2 + L) x = M y/h^2 + J d); the contact and the
/// damping enter through grad E, so the iteration's fixed point is the backward Euler step
/// itself. Particles that have touched the object get the contact weight 2 k_collision on
/// their diagonal (a refactorisation when one joins). With `chebyshev`, Wang's semi-iterative
/// acceleration ("A Chebyshev semi-iterative approach for accelerating projective and
/// position-based dynamics", ACM TOG 34(6), 2015) with spectral radius estimate `rho`. Then
/// velocity-level Coulomb friction (apply_friction) and the projection of docs/model.md
/// section 5. docs/integrators/projective-dynamics.md.
class ProjectiveDynamics final : public Integrator {
 public:
  /// Reads dt, max_steps and the keys iterations, chebyshev and rho from `options`.
  ProjectiveDynamics(ClothSystem& system, const IntegratorOptions& options);
  void reset(double t, const Eigen::VectorXd& y) override;
  double step(double t_stop) override;

  /// Records E at every iterate of the following steps (off by default: one energy evaluation
  /// per iteration).
  void record_potential(bool on) { m_record = on; }
  /// E(x_0), ..., E(x_K) of the last step while recording; E leaves out the spring damping
  /// (not a potential of x: its direction turns with x).
  const std::vector<double>& potential_trace() const { return m_trace; }

 private:
  /// Factors A again when the fixed set or the step size changed since the last factorisation.
  void update_factor(double h);
  /// Velocity-level Coulomb friction after the iterations (Bridson et al. 2002, section 7.2;
  /// docs/friction.md): the normal impulse h |F_c(x_{n+1})| cuts each free particle's
  /// tangential velocity, and its position follows, x_{n+1} = x_n + h v_{n+1}. A no-op without
  /// friction.
  void apply_friction(double h);
  /// Incremental potential at the positions of m_y (free particles' terms; the fixed ones'
  /// are constants of the step); in `magnitude` the sum of its terms' absolute values.
  double potential(double h, double& magnitude) const;
  double potential(double h) const;

  double m_dt;
  long m_max_steps;
  int m_iterations;
  bool m_chebyshev;
  double m_rho;
  double m_contact_weight;
  PdGlobalMatrix m_matrix;
  std::vector<unsigned char> m_factored_mask, m_contact;
  double m_factored_h = 0.0;
  bool m_factored = false;
  Eigen::VectorXd m_start, m_inertia, m_force, m_previous;  // 3N: x_n, x_n + h v_n, F, x_{k-1}
  std::vector<double> m_z;  // the global step's right side and solution, 3 per slot
  bool m_record = false;
  std::vector<double> m_trace;
};

/// The `projective-dynamics` declaration: family optimisation, keys iterations, chebyshev, rho.
IntegratorDeclaration projective_dynamics_declaration();

}  // namespace drape
