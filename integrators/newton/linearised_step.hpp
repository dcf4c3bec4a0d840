#pragma once
// One linearised implicit step of the cloth ODE y' = f(t, y), y = [x; v], shared by the
// integrators that take a single Newton step a step (implicit-euler, bdf2). The step's implicit
// equation
//     y_{n+1} = a + gamma f(t_{n+1}, y_{n+1}),   a = y_n + d
// (backward Euler: gamma = h, d = 0; BDF2: gamma = 2/3 h, d = (y_n - y_{n-1}) / 3) is linearised
// once about a start z_0 (y_n, as Baraff and Witkin and Choi and Ko do, or a predictor),
//     (I - gamma J(z_0)) dy = gamma f(z_0) + (a - z_0),   y_{n+1} = z_0 + dy,
// and solved on the 3N velocities by ReducedNewtonSolver, S = M - gamma D - gamma^2 K (Baraff
// and Witkin 1998, "Large steps in cloth simulation", section 4; Choi and Ko 2002, "Stable but
// responsive cloth", section 3). A fixed particle's rows are the identity, so its increment is
// set to the exact prescribed motion instead.
#include <Eigen/Core>

#include "core/model/cloth_system.hpp"
#include "integrators/interface/integrator.hpp"
#include "integrators/linear/reduced_newton_solver.hpp"

namespace drape {

/// Takes linearised implicit steps with a ReducedNewtonSolver it does not own.
class LinearisedStep {
 public:
  LinearisedStep(const ClothSystem& system, ReducedNewtonSolver& solver)
      : m_system(system), m_solver(solver) {}

  /// y += dy for the step of size h from t with `gamma`, started from z_0 = y; `known` is
  /// a - z_0 (null for none: a = z_0 = y_n, backward Euler from y_n), its fixed particles' rows
  /// unused (their dy is the prescribed motion to t + h). f is evaluated at time t: the time
  /// reaches only the fixed particles' rows, which are replaced. Books one rhs evaluation,
  /// Jacobian setup and Newton iteration, the CG iterations, and a convergence failure when CG
  /// stops at its iteration limit.
  void take(double t, double h, double gamma, const Eigen::VectorXd* known, Eigen::VectorXd& y,
            IntegratorCounters& counters);

 private:
  const ClothSystem& m_system;
  ReducedNewtonSolver& m_solver;
  Eigen::VectorXd m_residual, m_increment;
};

}  // namespace drape
