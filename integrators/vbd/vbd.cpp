#include "integrators/vbd/vbd.hpp"

#include <algorithm>

#include "integrators/acceleration/chebyshev.hpp"

namespace drape {

namespace {

VbdStart start_named(const std::string& name) {
  if (name == "previous") return VbdStart::previous;
  if (name == "velocity") return VbdStart::velocity;
  if (name == "adaptive") return VbdStart::adaptive;
  return VbdStart::inertia;
}

// Its own keys (IntegratorDeclaration::keys), built once: the declaration lists them and the
// constructor reads its settings against them.
const std::vector<SettingKey> own_keys = {
    SettingKey::integer("iterations", 20, 1, 100000,
                        "Gauss-Seidel sweeps over the particles per step"),
    SettingKey::choice("init", "velocity", {"inertia", "previous", "velocity", "adaptive"},
                       "start of a step's iterations: x_n + h v_n + h^2 g, x_n, x_n + h v_n, "
                       "or the paper's adaptive acceleration start"),
    SettingKey::boolean("chebyshev", false, "Chebyshev acceleration of the sweeps (Wang 2015)"),
    SettingKey::number("rho", 0.95, 0.0, 1.0,
                       "Chebyshev's estimate of the sweeps' spectral radius", true, true)};

}  // namespace

Vbd::Vbd(ClothSystem& system, const IntegratorOptions& options)
    : Integrator(system),
      m_dt(options.dt),
      m_iterations(static_cast<int>(options.setting_integer("iterations", own_keys))),
      m_start(start_named(options.setting_choice("init", own_keys))),
      m_chebyshev(options.setting_flag("chebyshev", own_keys)),
      m_rho(options.setting_number("rho", own_keys)),
      m_descent(system) {}

void Vbd::reset(double t, const Eigen::VectorXd& y) {
  Integrator::reset(t, y);
  const Eigen::Index n3 = y.size() / 2;
  m_x_n.resize(n3);
  m_v_n.resize(n3);
  m_previous_velocity.resize(n3);
  m_older.resize(n3);
  m_old.resize(n3);
  m_previous_step = 0.0;  // an event changed the motion: no acceleration to carry over
}

void Vbd::start_positions(double h, double t_next, VecRef x) {
  const Vec3 g = m_system.params().gravity;
  const double g2 = g.squaredNorm();
  const auto& fixed = m_system.constraints().mask();
  for (int i = 0; i < m_system.num_particles(); ++i) {
    if (fixed[static_cast<std::size_t>(i)]) {
      particle(x, i) = m_system.constraints().trajectory(i)->position(t_next);
      continue;
    }
    const Vec3 y = particle(m_x_n, i) + h * particle(m_v_n, i);
    double weight = 1.0;  // of h^2 g
    switch (m_start) {
      case VbdStart::inertia:
        break;
      case VbdStart::previous:
        particle(x, i) = particle(m_x_n, i);
        continue;
      case VbdStart::velocity:
        weight = 0.0;
        break;
      case VbdStart::adaptive:
        // The paper's section 3.6: the part of the last step's acceleration along gravity,
        // clamped to [0, |g|], so that a particle resting on the object (acceleration 0) starts
        // where it is and a falling one where gravity takes it. Without a last step (the start,
        // after an event), the inertial start.
        if (m_previous_step > 0.0 && g2 > 0.0) {
          const Vec3 a = (particle(m_v_n, i) - particle(m_previous_velocity, i)) / m_previous_step;
          weight = std::clamp(a.dot(g) / g2, 0.0, 1.0);
        }
        break;
    }
    particle(x, i) = y + (weight * h * h) * g;
  }
}

void Vbd::accelerate(int k, double& omega, VecRef x) {
  omega = chebyshev_omega(k, m_rho, omega);
  const auto& fixed = m_system.constraints().mask();
  if (k >= 2)
    for (int i = 0; i < m_system.num_particles(); ++i)
      if (!fixed[static_cast<std::size_t>(i)])
        particle(x, i) = omega * (particle(x, i) - particle(m_older, i)) + particle(m_older, i);
  m_older.swap(m_old);
  m_old = x;
}

double Vbd::step(double t_stop) {
  const double t_next = fixed_step_end(m_dt, m_t, t_stop);
  const double h = t_next - m_t;
  VecMap x = positions(), v = velocities();
  m_x_n = x;
  m_v_n = v;
  m_descent.begin_step(h, m_x_n, m_v_n);
  // IPC's lagged friction of the step (docs/model.md section 4.12), part of G's contact term.
  m_system.freeze_friction(m_x_n, h);
  start_positions(h, t_next, x);
  m_guess = x;
  if (m_chebyshev) m_old = x;  // x^(0); x^(-1) is never read
  double omega = 1.0;
  for (int k = 1; k <= m_iterations; ++k) {
    m_counters.line_search_backtracks += m_descent.sweep(x);
    if (m_chebyshev) accelerate(k, omega, x);
  }
  // G from the start to the last iterate, both with the last sweep's damping directions: two
  // evaluations a step, none a sweep.
  const VertexBlockPotential& potential = m_descent.potential();
  double start_terms = 0.0, end_terms = 0.0;
  const double start = potential.value(m_guess, start_terms);
  const double end = potential.value(x, end_terms);
  m_counters.add_potential_change(start, end, std::max(start_terms, end_terms));
  // One force and Jacobian-block evaluation of every particle per sweep.
  m_counters.newton_iters += m_iterations;
  m_counters.rhs_evals += m_iterations;
  m_counters.jacobian_setups += m_iterations;
  m_system.release_friction();
  v = (x - m_x_n) / h;
  m_system.project(t_next, x, v);
  m_previous_velocity = m_v_n;
  m_previous_step = h;
  return accept_fixed_step(t_next);
}

IntegratorDeclaration vbd_declaration() {
  return {
      "vbd",
      "optimisation",
      1,
      false,
      "Vertex Block Descent (Chen et al. 2024): Gauss-Seidel 3x3 Newton steps on backward "
      "Euler's incremental potential",
      own_keys,
      [](ClothSystem& system, const IntegratorOptions& options) -> std::unique_ptr<Integrator> {
        return std::make_unique<Vbd>(system, options);
      }};
}

}  // namespace drape
