#include "integrators/bdf2/bdf2.hpp"

namespace drape {

namespace {

// The largest ratio w = h_{n+1} / h_n of the history's spacing that the variable-step formula
// is given: BDF2 stays zero-stable for ratios below 1 + sqrt(2) (Grigorieff 1983; Hairer,
// Norsett and Wanner, "Solving ODEs I", section III.5), and 2 keeps a margin.
constexpr double max_step_ratio = 2.0;

// implicit-euler's keys and defaults: the linear solver's and `solve`
// (docs/integrators/bdf2.md, "Keys").
const NamedKeys declared_keys = {false, false, true, true, false, "pcg-multigrid", 1e-3};

// Its own keys (IntegratorDeclaration::keys), built once: the declaration lists them and the
// constructor reads its settings against them.
const std::vector<SettingKey> own_keys = {SettingKey::choice(
    "linearise_about", "predictor", {"predictor", "current"},
    "solve = linearised: the one Newton iteration starts from the predictor (the extrapolation; "
    "at a start the body forces' step) or from y_n (Choi and Ko)")};

}  // namespace

Bdf2::Bdf2(ClothSystem& system, const IntegratorOptions& options)
    : Integrator(system),
      m_dt(options.dt),
      m_max_steps(options.max_steps),
      m_solver(system, *reduced_solve_named(linear_solver_of(options, declared_keys)),
               ForceSplit::all, linear_tolerance_of(options, declared_keys),
               options.max_linear_iters),
      m_linearised(system, m_solver),
      m_from_predictor(options.setting_choice("linearise_about", own_keys) == "predictor") {
  if (uses_line_search(options, declared_keys)) m_converged.emplace(system, m_solver, options);
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
  double w = 0.0;
  if (m_has_history) {
    w = h / (m_t - m_previous_t);
    m_history_term = (w * w / (1.0 + 2.0 * w)) * (m_y - m_previous);
    gamma = h * (1.0 + w) / (1.0 + 2.0 * w);
  }
  if (m_converged) {
    converged_step(t_next, gamma);
  } else {
    // IPC's lagged friction frozen at the step's start, as implicit-euler's (docs/friction.md).
    m_system.freeze_friction(positions(), h);
    // The one Newton iteration from z_0 with the known term a - z_0 (a = y_n + d): from y_n
    // (linearise_about = current) it is d, none at a start; from the predictor its offset.
    const Eigen::VectorXd* known = m_has_history ? &m_history_term : nullptr;
    if (m_from_predictor) {
      predict(t_next, h, w);
      known = &m_known;
    }
    m_linearised.take(m_t, h, gamma, known, m_y, m_counters);
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

void Bdf2::predict(double t_next, double h, double w) {
  const Eigen::Index n3 = m_y.size() / 2;
  if (m_has_history) {
    // The line through the two last points, y_p = y_n + w (y_n - y_{n-1}); the offset a - y_p
    // with a = y_n + d is (w^2 / (1 + 2w) - w) (y_n - y_{n-1}).
    m_known = (w * w / (1.0 + 2.0 * w) - w) * (m_y - m_previous);
    m_y += w * (m_y - m_previous);
  } else {
    // Implicit Euler's start from the body forces' step (gravity and air damping, not the
    // stiff springs and contact): v_p = v_n + h a_body, x_p = x_n + h v_p, the prediction of
    // XPBD and VBD (Macklin et al. 2016, algorithm 1; Chen et al. 2024, "Initialization"). It meets
    // the position rows x = x_n + h v of the step's equation, so the correction is in the
    // velocities. The offset a - y_p with a = y_n is [-h v_p; -h a_body].
    m_known.resize(m_y.size());
    m_system.rhs(m_t, m_y, m_known, ForceSplit::body);
    ++m_counters.rhs_evals;
    m_known.tail(n3) *= -h;
    m_y.tail(n3) -= m_known.tail(n3);
    m_known.head(n3) = -h * m_y.tail(n3);
    m_y.head(n3) -= m_known.head(n3);
  }
  // Fixed particles start on their prescribed state at t_next (their rows of the step are it).
  const ConstraintSet& constraints = m_system.constraints();
  for (const int i : constraints.fixed_particles()) {
    const Trajectory& path = *constraints.trajectory(i);
    m_y.segment<3>(3 * i) = path.position(t_next);
    m_y.segment<3>(n3 + 3 * i) = path.velocity(t_next);
  }
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
          own_keys,
          [](ClothSystem& system, const IntegratorOptions& options) -> std::unique_ptr<Integrator> {
            return std::make_unique<Bdf2>(system, options);
          },
          declared_keys};
}

}  // namespace drape
