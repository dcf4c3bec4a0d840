#include "integrators/bdf2/bdf2.hpp"

namespace drape {

namespace {

// The largest ratio w = h_{n+1} / h_n of the history's spacing that the variable-step formula
// is given: BDF2 stays zero-stable for ratios below 1 + sqrt(2) (Grigorieff 1983; Hairer,
// Norsett and Wanner, "Solving ODEs I", section III.5), and 2 keeps a margin.
constexpr double max_step_ratio = 2.0;

}  // namespace

Bdf2::Bdf2(ClothSystem& system, const IntegratorOptions& options)
    : Integrator(system),
      m_dt(options.dt),
      m_max_steps(options.max_steps),
      m_solver(system, *reduced_solve_named(linear_solver_of(options)), ForceSplit::all,
               linear_tolerance_of(options), options.max_linear_iters),
      m_linearised(system, m_solver) {
  if (uses_line_search(options)) m_converged.emplace(system, m_solver, options);
}

void Bdf2::reset(double t, const Eigen::VectorXd& y) {
  Integrator::reset(t, y);
  m_has_history = false;  // the constraints changed: the next step is implicit Euler's
}

double Bdf2::step(double t_stop) {
  const double t_next = fixed_step_end(m_dt, m_t, t_stop);
  const double h = t_next - m_t;
  m_start = m_y;
  double gamma = h;  // without history: implicit Euler's step
  if (m_has_history) {
    const double w = h / (m_t - m_previous_t);
    m_history_term = (w * w / (1.0 + 2.0 * w)) * (m_y - m_previous);
    gamma = h * (1.0 + w) / (1.0 + 2.0 * w);
  }
  if (m_converged) {
    converged_step(t_next, gamma);
  } else {
    // IPC's lagged friction frozen at the step's start, as implicit-euler's (docs/friction.md).
    m_system.freeze_friction(positions(), h);
    m_linearised.take(m_t, h, gamma, m_has_history ? &m_history_term : nullptr, m_y,
                      m_counters);
    m_system.release_friction();
    m_system.project(t_next, positions(), velocities());
  }
  // A step cut short (a sliver before an output or event time) is not kept as the history's
  // spacing: the next full step would see a ratio w far above max_step_ratio. The older point
  // stays, so the spacing only grows and w stays at most max_step_ratio; without history the
  // next step is implicit Euler's again.
  if (h * max_step_ratio >= m_dt) {
    std::swap(m_previous, m_start);
    m_previous_t = m_t;
    m_has_history = true;
  }
  return accept_fixed_step(t_next);
}

void Bdf2::converged_step(double t_next, double gamma) {
  const auto check = [this] { check_attempts(m_max_steps); };
  if (m_has_history) {
    check();
    try {
      m_known = m_y + m_history_term;  // a = y_n + d
      m_converged->solve(m_t, t_next, gamma, m_known, m_y, m_counters, "BDF2's equation");
      m_system.project(t_next, positions(), velocities());
      return;
    } catch (const IntegratorFailure&) {
      if (!m_converged->halves()) throw;
    }
    // The failed attempt stays counted; the interval is taken by converged backward Euler,
    // halved where it fails too, and the history y_n stays valid for the next step.
    ++m_counters.attempts;
  }
  m_converged->cover_backward_euler(m_t, t_next, m_y, m_counters, check);
  // The cover counted each of its steps; accept_fixed_step counts the interval once more.
  --m_counters.steps;
  --m_counters.attempts;
}

IntegratorDeclaration bdf2_declaration() {
  return {"bdf2", "implicit", 2, false,
          "Choi-Ko BDF2, linearised (one solve a step, CG or sparse LDLT on the 3N velocity "
          "system) or converged by the line-search Newton",
          {},
          [](ClothSystem& system, const IntegratorOptions& options) -> std::unique_ptr<Integrator> {
            return std::make_unique<Bdf2>(system, options);
          },
          // implicit-euler's keys and defaults: the linear solver's and `solve`
          // (docs/integrators/bdf2.md, "Keys")
          {false, false, true, true, false, "pcg-multigrid", 1e-3},
          true};
}

}  // namespace drape
