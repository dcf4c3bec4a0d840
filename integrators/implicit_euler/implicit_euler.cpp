#include "integrators/implicit_euler/implicit_euler.hpp"

namespace drape {

ImplicitEuler::ImplicitEuler(ClothSystem& system, const IntegratorOptions& options)
    : Integrator(system),
      m_options(options),
      m_dt(options.dt),
      m_solver(system, *reduced_solve_named(linear_solver_of(options)), ForceSplit::all,
               linear_tolerance_of(options), options.max_linear_iters),
      m_linearised(system, m_solver) {
  if (uses_line_search(options))
    m_line_search.emplace(system, ForceSplit::all, m_solver,
                          *exact_solve_named(exact_solve_of(options)));
}

double ImplicitEuler::step(double t_stop) {
  const double t_next = fixed_step_end(m_dt, m_t, t_stop);
  if (m_line_search) {
    cover_converged(m_t, t_next, m_options.max_step_halvings);
    // cover_converged counted every solve (a halved interval's sub-steps are steps, as in
    // ARKODE's counters); accept_fixed_step counts the interval once more.
    --m_counters.steps;
    --m_counters.attempts;
  } else {
    // One Newton step of y_{n+1} = y_n + h f(y_{n+1}) from y_n: Baraff and Witkin's system.
    m_system.freeze_friction(positions(), t_next - m_t);
    m_linearised.take(m_t, t_next - m_t, t_next - m_t, nullptr, m_y, m_counters);
    m_system.release_friction();
    m_system.project(t_next, positions(), velocities());
  }
  return accept_fixed_step(t_next);
}

// The interval as one backward-Euler step or, when its stage solve fails, as two halves, each
// halved again up to max_step_halvings levels: the rule of ARKODE's fixed steps
// (arkode_stepper.cpp, cover_fixed), so that a converged implicit-euler and a one-stage DIRK
// table meet a hard step alike (docs/integrators/arkode.md, "Fixed steps that fail are halved").
void ImplicitEuler::cover_converged(double t_start, double t_end, int halvings_left) {
  check_attempts(m_options.max_steps);
  ++m_counters.attempts;
  try {
    converged_step(t_start, t_end);
    m_system.project(t_end, positions(), velocities());
    ++m_counters.steps;
    return;
  } catch (const IntegratorFailure& failure) {
    if (m_options.max_step_halvings == 0) throw;
    if (halvings_left == 0)
      throw IntegratorFailure(failure.flag(),
                              std::string(failure.what()) + " (the step was halved " +
                                  std::to_string(m_options.max_step_halvings) + " times, to " +
                                  std::to_string(t_end - t_start) + " s)");
  }
  ++m_counters.step_halvings;  // m_y is still the interval's start: a failed solve keeps it
  const double middle = t_start + 0.5 * (t_end - t_start);
  cover_converged(t_start, middle, halvings_left - 1);
  cover_converged(middle, t_end, halvings_left - 1);
}

void ImplicitEuler::converged_step(double t_start, double t_next) {
  // ARKODE's error weights and its default Newton tolerance (nlscoef 0.1), so that a converged
  // implicit-euler and a one-stage ARKODE table stop at the same accuracy.
  constexpr double tolerance = 0.1;
  m_weights = 1.0 / (m_options.rtol * m_y.array().abs() + m_options.atol);
  m_increment = m_y;  // the stage's guess: the step's start
  const long cg_before = m_solver.iterations();
  // IPC's lagged friction (docs/model.md section 4.12): normal forces and tangents of the step's
  // start, so that the stage stays the minimum of one potential.
  m_system.freeze_friction(positions(), t_next - t_start);
  const StageSolve result =
      m_line_search->solve(t_next, t_next - t_start, m_y, m_increment,
                           StageTolerance{m_weights, tolerance, max_newton_iters_of(m_options)});
  m_system.release_friction();
  m_counters.linear_iters += m_solver.iterations() - cg_before + result.krylov_iterations;
  m_counters.newton_iters += result.iterations;
  m_counters.rhs_evals += result.rhs_evals;
  m_counters.jacobian_setups += result.setups;
  m_counters.line_search_backtracks += result.backtracks;
  if (!result.converged) {
    ++m_counters.convergence_failures;
    throw IntegratorFailure("CONV_FAILURE",
                            "implicit-euler: backward Euler did not converge in " +
                                std::to_string(result.iterations) + " Newton iterations at t = " +
                                std::to_string(t_next) + ": stopped by " + result.stopped_by);
  }
  m_y = m_increment;
}

}  // namespace drape
