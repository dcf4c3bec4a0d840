#include "integrators/newton/converged_step.hpp"

#include <algorithm>
#include <string>

namespace drape {

namespace {

// ARKODE's default Newton tolerance (nlscoef 0.1) on the weighted RMS norm of the update.
constexpr double tolerance = 0.1;

}  // namespace

ConvergedStep::ConvergedStep(ClothSystem& system, ReducedNewtonSolver& solver,
                             const IntegratorOptions& options)
    : m_system(system),
      m_solver(solver),
      m_name(options.name),
      m_rtol(options.rtol),
      m_atol(options.atol),
      m_max_newton_iters(max_newton_iters_of(options, /*line_search=*/true)),
      m_max_step_halvings(options.max_step_halvings),
      m_line_search(system, ForceSplit::all, solver, *exact_solve_named(exact_solve_of(options))) {}

void ConvergedStep::solve(double t_start, double t_next, double gamma, ConstVecRef a,
                          Eigen::VectorXd& y, IntegratorCounters& counters, const char* equation) {
  const Eigen::Index n3 = y.size() / 2;
  m_weights = 1.0 / (m_rtol * y.array().abs() + m_atol);
  m_stage = y;  // the stage's guess: the step's start
  const long cg_before = m_solver.iterations();
  // IPC's lagged friction (docs/model.md section 4.12): normal forces and tangents of the step's
  // start, so that the stage stays the minimum of one potential.
  m_system.freeze_friction(y.head(n3), t_next - t_start);
  const StageSolve result = m_line_search.solve(
      t_next, gamma, a, m_stage, StageTolerance{m_weights, tolerance, m_max_newton_iters});
  counters.linear_iters += m_solver.iterations() - cg_before + result.krylov_iterations;
  counters.newton_iters += result.iterations;
  counters.rhs_evals += result.rhs_evals;
  counters.jacobian_setups += result.setups;
  counters.line_search_backtracks += result.backtracks;
  if (!result.converged) {
    m_system.release_friction();
    ++counters.convergence_failures;
    throw IntegratorFailure("CONV_FAILURE", m_name + ": " + equation +
                                                " did not converge in " +
                                                std::to_string(result.iterations) +
                                                " Newton iterations at t = " +
                                                std::to_string(t_next) + ": stopped by " +
                                                result.stopped_by);
  }
  // The potential's change from the guess to the solution, both on the last iteration's E_k
  // (its damping directions frozen there; the guess as begin_stage set it: its own free
  // velocities, the fixed rows' stage values): two evaluations a step, none an iteration.
  const IncrementalPotential& potential = m_line_search.potential();
  m_guess = m_stage;
  potential.state_of(y.tail(n3), m_guess);
  double start_terms = 0.0, end_terms = 0.0;
  const double start = potential.value(m_guess, start_terms);
  const double end = potential.value(m_stage, end_terms);
  counters.add_potential_change(start, end, std::max(start_terms, end_terms));
  m_system.release_friction();
  y = m_stage;
}

void ConvergedStep::cover_backward_euler(double t_start, double t_end, Eigen::VectorXd& y,
                                         IntegratorCounters& counters,
                                         const std::function<void()>& before_attempt) {
  cover(t_start, t_end, m_max_step_halvings, y, counters, before_attempt);
}

void ConvergedStep::cover(double t_start, double t_end, int halvings_left, Eigen::VectorXd& y,
                          IntegratorCounters& counters,
                          const std::function<void()>& before_attempt) {
  before_attempt();
  ++counters.attempts;
  const Eigen::Index n3 = y.size() / 2;
  try {
    solve(t_start, t_end, t_end - t_start, y, y, counters, "backward Euler");
    m_system.project(t_end, VecMap(y.data(), n3), VecMap(y.data() + n3, n3));
    ++counters.steps;
    return;
  } catch (const IntegratorFailure& failure) {
    if (m_max_step_halvings == 0) throw;
    if (halvings_left == 0)
      throw IntegratorFailure(failure.flag(),
                              std::string(failure.what()) + " (the step was halved " +
                                  std::to_string(m_max_step_halvings) + " times, to " +
                                  std::to_string(t_end - t_start) + " s)");
  }
  ++counters.step_halvings;  // y is still the interval's start: a failed solve keeps it
  const double middle = t_start + 0.5 * (t_end - t_start);
  cover(t_start, middle, halvings_left - 1, y, counters, before_attempt);
  cover(middle, t_end, halvings_left - 1, y, counters, before_attempt);
}

}  // namespace drape
