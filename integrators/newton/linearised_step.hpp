#pragma once
// One linearised implicit step of the cloth ODE y' = f(t, y), y = [x; v], shared by the
// integrators that take a single Newton step a step (implicit-euler, bdf2). The step's implicit
// equation
//     y_{n+1} = y_n + d + gamma f(t_{n+1}, y_{n+1})
// (backward Euler: gamma = h, d = 0; BDF2: gamma = 2/3 h, d = (y_n - y_{n-1}) / 3) is linearised
// once about y_n,
//     (I - gamma J(y_n)) dy = gamma f(t_n, y_n) + d,   y_{n+1} = y_n + dy,
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

  /// y += dy for the step of size h from t with `gamma`; `history` is d (null for none). Books
  /// one rhs evaluation, Jacobian setup and Newton iteration, the CG iterations, and a
  /// convergence failure when CG stops at its iteration limit.
  void take(double t, double h, double gamma, const Eigen::VectorXd* history,
            Eigen::VectorXd& y, IntegratorCounters& counters);
  /// One Newton iteration of z = a + gamma f(t_next, z) started from a predictor z_0 = y
  /// instead of y_n: (I - gamma J(z_0)) dz = gamma f(t_next, z_0) + (a - z_0), y += dz;
  /// `offset` is a - z_0 (its fixed particles' rows unused: their dz is the prescribed motion
  /// to t_next). Books as take() does.
  void correct(double t_next, double gamma, const Eigen::VectorXd& offset, Eigen::VectorXd& y,
               IntegratorCounters& counters);

 private:
  /// The Newton iteration from y with f at t, fixed particles moved onto their path at t_next.
  void iterate(double t, double t_next, double gamma, const Eigen::VectorXd* offset,
               Eigen::VectorXd& y, IntegratorCounters& counters);

  const ClothSystem& m_system;
  ReducedNewtonSolver& m_solver;
  Eigen::VectorXd m_residual, m_increment;
};

}  // namespace drape
