#include "integrators/implicit_euler/implicit_euler.hpp"

namespace drape {

ImplicitEuler::ImplicitEuler(ClothSystem& system, const IntegratorOptions& options)
    : Integrator(system),
      m_max_steps(options.max_steps),
      m_dt(options.dt),
      m_solver(system, *reduced_solve_named(linear_solver_of(options)), ForceSplit::all,
               linear_tolerance_of(options), options.max_linear_iters),
      m_linearised(system, m_solver) {
  if (uses_line_search(options)) m_converged.emplace(system, m_solver, options);
}

double ImplicitEuler::step(double t_stop) {
  const double t_next = fixed_step_end(m_dt, m_t, t_stop);
  if (m_converged) {
    m_converged->cover_backward_euler(m_t, t_next, m_y, m_counters,
                                      [this] { check_attempts(m_max_steps); });
    // The cover counted every solve (a halved interval's sub-steps are steps, as in ARKODE's
    // counters); accept_fixed_step counts the interval once more.
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

}  // namespace drape
