#pragma once
// Implicit steps y_{n+1} = a + gamma f(t_{n+1}, y_{n+1}) solved to convergence, shared by the
// integrators whose `solve` = converged (implicit-euler: backward Euler, a = y_n, gamma = h;
// bdf2: a = y_n + d, gamma = 2/3 h, docs/integrators/bdf2.md). The stage is minimised by the
// line-search Newton of the ARKODE stages (line_search_newton.hpp) until its update is within
// ARKODE's test: error weights 1 / (rtol |y_n| + atol) and tolerance 0.1 (nlscoef), so that a
// converged step and a one-stage ARKODE table stop at the same accuracy.
#include <Eigen/Core>
#include <functional>
#include <string>

#include "integrators/interface/integrator.hpp"
#include "integrators/interface/integrator_options.hpp"
#include "integrators/newton/line_search_newton.hpp"

namespace drape {

/// Converged implicit steps with a ReducedNewtonSolver it does not own.
class ConvergedStep {
 public:
  /// Reads name, rtol, atol, max_newton_iters, exact_solve and max_step_halvings.
  ConvergedStep(ClothSystem& system, ReducedNewtonSolver& solver, const IntegratorOptions& options);

  /// y_{n+1} = a + gamma f(t_next, y_{n+1}) from the guess y (the state at t_start), into y,
  /// not projected. Books the solve's counters and its incremental potential's change
  /// (IntegratorCounters::add_potential_change). Throws IntegratorFailure naming `equation`
  /// when the solve does not converge; y is then unchanged.
  void solve(double t_start, double t_next, double gamma, ConstVecRef a, Eigen::VectorXd& y,
             IntegratorCounters& counters, const char* equation);
  /// [t_start, t_end] from y by backward Euler steps (a = y, gamma = h) each solved by solve()
  /// and projected; where a solve fails the interval is taken as two halves, each halved again
  /// up to max_step_halvings levels (ARKODE's rule for fixed steps, arkode_stepper.cpp,
  /// cover_fixed). `before_attempt` runs before every attempt (the integrator's
  /// check_attempts); each solve counts as an attempt and, when it converges, a step.
  void cover_backward_euler(double t_start, double t_end, Eigen::VectorXd& y,
                            IntegratorCounters& counters,
                            const std::function<void()>& before_attempt);
  /// Whether a failed solve may be retried on halves (max_step_halvings > 0).
  bool halves() const { return m_max_step_halvings > 0; }

 private:
  void cover(double t_start, double t_end, int halvings_left, Eigen::VectorXd& y,
             IntegratorCounters& counters, const std::function<void()>& before_attempt);

  ClothSystem& m_system;
  ReducedNewtonSolver& m_solver;
  std::string m_name;
  double m_rtol, m_atol;
  int m_max_newton_iters, m_max_step_halvings;
  LineSearchNewton m_line_search;
  Eigen::VectorXd m_weights, m_stage, m_guess;
};

}  // namespace drape
