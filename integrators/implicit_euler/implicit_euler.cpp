#include "integrators/implicit_euler/implicit_euler.hpp"

namespace drape {

namespace {

// pcg-multigrid, measured on the draped-cloth benchmark (docs/integrators/linear-solvers.md): the
// multigrid cycle pays for itself at implicit-euler's large steps (90 -> 9 CG iterations at
// 1/30 s); ARKODE's adaptive steps there are microseconds, S is then close to M, and block Jacobi
// is cheaper. 1e-3: integrator_options.hpp, linear_tolerance_of.
const NamedKeys declared_keys = {false, false, true, true, false, "pcg-multigrid", 1e-3};

}  // namespace

ImplicitEuler::ImplicitEuler(ClothSystem& system, const IntegratorOptions& options)
    : Integrator(system),
      m_max_steps(options.max_steps),
      m_dt(options.dt),
      m_solver(system, *reduced_solve_named(linear_solver_of(options, declared_keys)),
               ForceSplit::all, linear_tolerance_of(options, declared_keys),
               options.max_linear_iters),
      m_linearised(system, m_solver) {
  if (uses_line_search(options, declared_keys)) m_converged.emplace(system, m_solver, options);
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

IntegratorDeclaration implicit_euler_declaration() {
  return {"implicit-euler", "implicit", 1, false,
          "Baraff-Witkin linearised backward Euler, CG or sparse LDLT on the 3N velocity system",
          {},
          [](ClothSystem& system, const IntegratorOptions& options) -> std::unique_ptr<Integrator> {
            return std::make_unique<ImplicitEuler>(system, options);
          },
          declared_keys};
}

}  // namespace drape
