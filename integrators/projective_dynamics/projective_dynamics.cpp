#include "integrators/projective_dynamics/projective_dynamics.hpp"

#include <algorithm>
#include <cmath>

#include "core/parallel/fixed_block_sum.hpp"
#include "integrators/acceleration/chebyshev.hpp"

namespace drape {

namespace {

// Springs, gravity and air damping from the model's force loop; the contact is added per free
// particle in the gather, where a new contact is seen.
constexpr ForceSplit without_collision{true, false, true, false};

// A step size within this relative distance of the factored one keeps the factor: a fixed
// step's last piece before t_stop differs from dt by round-off only. The iteration's fixed
// point does not depend on A, only its speed does.
constexpr double same_step = 1e-6;

// Its own keys (IntegratorDeclaration::keys), built once: the declaration lists them and the
// constructor reads its settings against them.
const std::vector<SettingKey> own_keys = {
    SettingKey::integer("iterations", 10, 1, 100000, "local/global iterations per step"),
    SettingKey::boolean("chebyshev", false, "Chebyshev semi-iterative acceleration (Wang 2015)"),
    SettingKey::number("rho", 0.9, 0.0, 1.0,
                       "spectral radius estimate of the Chebyshev acceleration", true, true)};

}  // namespace

ProjectiveDynamics::ProjectiveDynamics(ClothSystem& system, const IntegratorOptions& options)
    : Integrator(system),
      m_dt(options.dt),
      m_max_steps(options.max_steps),
      m_iterations(static_cast<int>(options.setting_integer("iterations", own_keys))),
      m_chebyshev(options.setting_flag("chebyshev", own_keys)),
      m_rho(options.setting_number("rho", own_keys)),
      // The smooth model's normal stiffness reaches 2 k (its energy k/(3 delta) (delta - G)^3
      // continued quadratically inside); the particle and surface models' is k. The weight keeps
      // A above the contact's Hessian, so the iteration does not overshoot a contact.
      m_contact_weight(system.dummy() ? 2.0 * system.params().collision.stiffness : 0.0),
      m_matrix(system.cloth().springs, m_contact_weight) {}

void ProjectiveDynamics::reset(double t, const Eigen::VectorXd& y) {
  Integrator::reset(t, y);
  const Eigen::Index n3 = y.size() / 2;
  m_start.resize(n3);
  m_inertia.resize(n3);
  m_force.resize(n3);
  m_previous.resize(n3);
  m_z.resize(static_cast<std::size_t>(n3));
  m_contact.resize(static_cast<std::size_t>(m_system.num_particles()), 0);
  m_trace.reserve(static_cast<std::size_t>(m_iterations) + 1);
}

void ProjectiveDynamics::update_factor(double h) {
  const std::vector<unsigned char>& mask = m_system.constraints().mask();
  if (m_factored && mask == m_factored_mask && std::abs(h / m_factored_h - 1.0) <= same_step)
    return;
  const ClothParams& p = m_system.cloth().params;
  // Air damping's Rayleigh term c_air |x - x_n|^2 / (2h) is isotropic: exactly in A. Spring
  // damping's c_s ((dx_j - dx_i) . u)^2 / (2h) has Hessian c_s/h u u^T <= c_s/h I: A takes the
  // bound, so that it stays above E's Hessian (the exact term is in the gradient).
  m_matrix.factor(mask, m_contact, m_system.particle_mass() / (h * h) + p.damping_air / h,
                  p.damping_spring / h);
  m_factored_mask = mask;
  m_factored_h = h;
  m_factored = true;
  ++m_counters.jacobian_setups;
}

double ProjectiveDynamics::step(double t_stop) {
  check_attempts(m_max_steps);
  const double t_next = fixed_step_end(m_dt, m_t, t_stop);
  const double h = t_next - m_t;
  update_factor(h);
  const ConstraintSet& constraints = m_system.constraints();
  const Collision& collision = m_system.collision();
  const bool with_contact = m_system.dummy() != nullptr;
  const double m = m_system.particle_mass();
  const double inertia_weight = m / (h * h);
  VecMap x = positions(), v = velocities();
  m_start = x;
  // The start x_0: y = x_n + h v_n for free particles (Liu et al. 2013, section 4; adding
  // h^2 g would move a cloth at rest in its equilibrium, which y keeps exactly), the known
  // p(t_{n+1}), p'(t_{n+1}) for fixed ones (they are no unknowns).
  for (const int i : m_matrix.slots()) {
    particle(m_inertia, i) = particle(x, i) + h * particle(v, i);
    particle(x, i) = particle(m_inertia, i);
  }
  for (const int i : constraints.fixed_particles()) {
    particle(x, i) = constraints.trajectory(i)->position(t_next);
    particle(v, i) = constraints.trajectory(i)->velocity(t_next);
  }
  m_trace.clear();
  double start_terms = 0.0;
  const double start = potential(h, start_terms);
  if (m_record) m_trace.push_back(start);
  double omega = 1.0;  // Chebyshev's weight of loop index k is Wang's omega_{k+1}
  const std::vector<int>& slots = m_matrix.slots();
  const auto free_count = static_cast<std::ptrdiff_t>(slots.size());
  for (int k = 0; k < m_iterations; ++k) {
    if (m_record && k > 0) m_trace.push_back(potential(h));
    m_system.forces(x, v, m_force, without_collision);
    ++m_counters.rhs_evals;
    // -grad E = F(x, (x - x_n)/h) - M/h^2 (x - x_n - h v_n), gathered in the factor's order.
    // The local step, per particle on threads (core/parallel); a new contact is counted as a
    // fixed-block sum, whose value does not depend on the order anyway.
    const double new_contacts = fixed_block_sum(
        free_count, particles_per_block, [&](std::ptrdiff_t begin, std::ptrdiff_t end) {
          double count = 0.0;
          for (std::ptrdiff_t s = begin; s < end; ++s) {
            const int i = slots[static_cast<std::size_t>(s)];
            Vec3 r =
                particle(m_force, i) - inertia_weight * (particle(x, i) - particle(m_inertia, i));
            if (with_contact) {
              const Vec3 push = collision.force(i, particle(x, i));
              if (push.squaredNorm() > 0.0) {
                r += push;
                if (!m_contact[static_cast<std::size_t>(i)])
                  m_contact[static_cast<std::size_t>(i)] = 1, count += 1.0;
              }
            }
            Eigen::Map<Vec3>(m_z.data() + 3 * s) = r;
          }
          return count;
        });
    if (new_contacts > 0.0) {
      m_matrix.refactor(m_contact);
      ++m_counters.jacobian_setups;
    }
    m_matrix.solve_in_place(m_z.data());
    if (m_chebyshev) omega = chebyshev_omega(k + 1, m_rho, omega);
    const double size = fixed_block_sum(
        free_count, particles_per_block, [&](std::ptrdiff_t begin, std::ptrdiff_t end) {
          double sum = 0.0;
          for (std::ptrdiff_t s = begin; s < end; ++s) {
            const int i = slots[static_cast<std::size_t>(s)];
            const Eigen::Map<const Vec3> dx(m_z.data() + 3 * s);
            sum += dx.squaredNorm();
            Vec3 next = particle(x, i) + dx;
            if (m_chebyshev) {
              if (k > 0) next = omega * (next - particle(m_previous, i)) + particle(m_previous, i);
              particle(m_previous, i) = particle(x, i);
            }
            particle(x, i) = next;
            particle(v, i) = (next - particle(m_start, i)) / h;
          }
          return sum;
        });
    if (!std::isfinite(size))
      throw IntegratorFailure("pd_not_finite", "projective-dynamics: a non-finite iterate at t = " +
                                                   std::to_string(t_next));
  }
  double end_terms = 0.0;
  const double end = potential(h, end_terms);
  if (m_record) m_trace.push_back(end);
  m_counters.add_potential_change(start, end, std::max(start_terms, end_terms));
  m_counters.newton_iters += m_iterations;
  apply_friction(h);
  m_system.project(t_next, x, v);
  return accept_fixed_step(t_next);
}

void ProjectiveDynamics::apply_friction(double h) {
  if (m_system.friction().coefficient() == 0.0) return;
  VecMap x = positions(), v = velocities();
  m_system.apply_velocity_friction(x, v, h);
  // The step's positions follow its velocities (x = x_n + h v, backward Euler's relation), so
  // that a particle whose tangential velocity friction stopped has not moved along the surface.
  for (const int i : m_matrix.slots()) particle(x, i) = particle(m_start, i) + h * particle(v, i);
}

double ProjectiveDynamics::potential(double h) const {
  double magnitude = 0.0;
  return potential(h, magnitude);
}

double ProjectiveDynamics::potential(double h, double& magnitude) const {
  const Eigen::Index n3 = m_y.size() / 2;
  const ConstVecMap x(m_y.data(), n3);
  const double m = m_system.particle_mass();
  const double c_air = m_system.cloth().params.damping_air;
  double inertia = 0.0, air = 0.0;
  for (const int i : m_matrix.slots()) {
    inertia += (particle(x, i) - particle(m_inertia, i)).squaredNorm();
    air += (particle(x, i) - particle(m_start, i)).squaredNorm();
  }
  const EnergyBreakdown e = m_system.energy(x, Eigen::VectorXd::Zero(n3));
  const double kinetic = m / (2.0 * h * h) * inertia + c_air / (2.0 * h) * air;
  magnitude = kinetic + e.spring + std::abs(e.gravity) + e.collision;
  return kinetic + e.spring + e.gravity + e.collision;
}

IntegratorDeclaration projective_dynamics_declaration() {
  return {"projective-dynamics", "optimisation", 1, false,
          "Projective Dynamics (Liu et al. 2013, Bouaziz et al. 2014): local/global iterations "
          "towards backward Euler, one sparse Cholesky per fixed set",
          own_keys,
          [](ClothSystem& system, const IntegratorOptions& options) -> std::unique_ptr<Integrator> {
            return std::make_unique<ProjectiveDynamics>(system, options);
          }};
}

}  // namespace drape
