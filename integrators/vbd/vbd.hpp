#pragma once
// Vertex Block Descent (Chen, Liu, Yang and Yuksel 2024, "Vertex Block Descent", ACM TOG 43(4)):
// backward Euler's incremental potential G (vertex_block_potential.hpp) minimised by
// Gauss-Seidel over the particles in graph-colour order, each particle by one Newton step on its
// 3x3 block, dx_i = H_i^-1 f_i, with the definite block Hessian H_i (>= M / h^2). A block step
// that raises G is halved (per-particle backtracking, the paper's optional line search), so
// that no block step raises G. Fixed particles sit at p(t_{n+1}) throughout. After
// `iterations` sweeps (optionally Chebyshev-accelerated, Wang 2015, "A Chebyshev semi-iterative
// approach for accelerating projective and position-based dynamics", ACM TOG 34(6)),
// v = (x - x_n) / h and the projection of docs/model.md section 5. As the sweeps go on, the step
// tends to converged backward Euler (implicit-euler, solve = converged).
#include "integrators/interface/integrator.hpp"
#include "integrators/interface/integrator_declaration.hpp"
#include "integrators/interface/integrator_options.hpp"
#include "integrators/vbd/vertex_block_descent.hpp"

namespace drape {

/// Where a step's iterations start (the paper's section 3.6).
enum class VbdStart {
  inertia,   ///< y + h^2 g: the inertial position with gravity
  previous,  ///< x_n
  velocity,  ///< y = x_n + h v_n
  adaptive,  ///< y + h^2 w g, w = clamp(a_n . g / |g|^2, 0, 1), a_n the last step's acceleration
};

/// The vbd integrator.
class Vbd final : public Integrator {
 public:
  /// Reads dt and the keys of vbd_declaration() from `options`.
  Vbd(ClothSystem& system, const IntegratorOptions& options);
  void reset(double t, const Eigen::VectorXd& y) override;
  double step(double t_stop) override;

 private:
  /// The free particles' start (m_start) and the fixed ones at p(t_next).
  void start_positions(double h, double t_next, VecRef x);
  /// Chebyshev's step after sweep k (1-based): x = omega (x - x^(k-2)) + x^(k-2).
  void accelerate(int k, double& omega, VecRef x);

  double m_dt;
  int m_iterations;
  VbdStart m_start;
  bool m_chebyshev;
  double m_rho;
  VertexBlockDescent m_descent;
  Eigen::VectorXd m_x_n, m_v_n, m_previous_velocity, m_older, m_old;
  Eigen::VectorXd m_guess;  // the step's start positions, for the potential's change
  double m_previous_step = 0.0;  // 0: no last step to take an acceleration from
};

/// vbd's declaration (name, family, keys: iterations, init, chebyshev, rho).
IntegratorDeclaration vbd_declaration();

}  // namespace drape
