#include "integrators/xpbd/xpbd.hpp"

#include <cmath>
#include <memory>

#include "core/collision/friction.hpp"
#include "core/forces/forces.hpp"
#include "core/parallel/parallel_for.hpp"
#include "integrators/colouring/graph_colouring.hpp"
#include "integrators/xpbd/xpbd_constraints.hpp"

namespace drape {

namespace {

// Its own keys (IntegratorDeclaration::keys), built once: the declaration lists them and the
// constructor reads its settings against them.
const std::vector<SettingKey> own_keys = {
    SettingKey::integer("substeps", 80, 1, 10000, "substeps per dt"),
    SettingKey::integer("iterations", 1, 1, 10000, "constraint sweeps per substep"),
    SettingKey::choice("sweep", "gauss-seidel", {"gauss-seidel", "jacobi"},
                       "gauss-seidel: springs in colour order, then contacts; jacobi: every "
                       "constraint from one iterate, relaxed")};

}  // namespace

Xpbd::Xpbd(ClothSystem& system, const IntegratorOptions& options)
    : Integrator(system),
      m_dt(options.dt),
      m_substeps(static_cast<int>(options.setting_integer("substeps", own_keys))),
      m_iterations(static_cast<int>(options.setting_integer("iterations", own_keys))),
      m_jacobi(options.setting_choice("sweep", own_keys) == "jacobi") {
  const SpringList& springs = system.cloth().springs;
  const int n = system.num_particles();
  const Eigen::Index count = springs.size();
  m_first.resize(count);
  m_second.resize(count);
  m_rest.resize(count);
  m_compliance.resize(count);
  m_damping_ratio.resize(count);
  const double damping = system.cloth().params.damping_spring;
  Eigen::Index e = 0;
  // The colour order is the only order: within a colour no two springs share a particle, so
  // the sweep's result is fixed by it (and a colour is split among threads, sweep()).
  for (const std::vector<int>& colour : colour_springs(n, springs)) {
    for (const int s : colour) {
      m_first[e] = springs.first[s];
      m_second[e] = springs.second[s];
      m_rest[e] = springs.rest[s];
      m_compliance[e] = 1.0 / springs.stiffness[s];
      // XPBD's beta of C = |d| - L0 with Rayleigh dissipation beta Cdot^2 / 2 is the model's
      // c_s (w . u)^2 / 2 (docs/model.md section 4.2): gamma = alpha beta / h = (c_s / k) / h.
      m_damping_ratio[e] = damping / springs.stiffness[s];
      ++e;
    }
    m_colour_end.push_back(e);
  }
  m_inverse_mass.resize(n);
  m_w_first.resize(count);
  m_w_second.resize(count);
  m_weight.resize(count);
  m_split_weight.resize(count);
  m_split_inverse_mass.resize(n);
  m_previous.resize(3 * n);
  m_correction.resize(3 * n);
  m_lambda.resize(count);
  m_contact_lambda.resize(n);
  m_free.reserve(static_cast<std::size_t>(n));
}

void Xpbd::reset(double t, const Eigen::VectorXd& y) {
  Integrator::reset(t, y);
  const int n = m_system.num_particles();
  const std::vector<unsigned char>& fixed = m_system.constraints().mask();
  const double inverse_mass = 1.0 / m_system.particle_mass();
  m_free.clear();
  for (int i = 0; i < n; ++i) {
    m_inverse_mass[i] = fixed[static_cast<std::size_t>(i)] ? 0.0 : inverse_mass;
    if (!fixed[static_cast<std::size_t>(i)]) m_free.push_back(i);
  }
  // Constraints touching each particle (its springs and its contact), for Jacobi's mass
  // splitting.
  Eigen::ArrayXd touching = Eigen::ArrayXd::Constant(n, m_system.dummy() ? 1.0 : 0.0);
  for (Eigen::Index e = 0; e < m_first.size(); ++e) {
    touching[m_first[e]] += 1.0;
    touching[m_second[e]] += 1.0;
    m_w_first[e] = m_inverse_mass[m_first[e]];
    m_w_second[e] = m_inverse_mass[m_second[e]];
  }
  m_weight = m_w_first + m_w_second;
  for (Eigen::Index e = 0; e < m_first.size(); ++e)
    m_split_weight[e] = touching[m_first[e]] * m_w_first[e] + touching[m_second[e]] * m_w_second[e];
  m_split_inverse_mass = touching * m_inverse_mass;
}

double Xpbd::step(double t_stop) {
  const double t_next = fixed_step_end(m_dt, m_t, t_stop);
  const double h = (t_next - m_t) / m_substeps;
  for (int s = 1; s < m_substeps; ++s) substep(m_t + s * h, h);
  substep(t_next, h);
  VecMap x = positions(), v = velocities();
  m_system.project(t_next, x, v);
  // A sweep evaluates every spring and contact once, as a force evaluation does.
  const long sweeps = static_cast<long>(m_substeps) * m_iterations;
  m_counters.newton_iters += sweeps;
  m_counters.rhs_evals += sweeps;
  return accept_fixed_step(t_next);
}

void Xpbd::substep(double t_sub, double h) {
  VecMap x = positions(), v = velocities();
  m_previous = x;
  const Vec3 gravity_kick = h * m_system.params().gravity;
  // Air damping by backward Euler on the velocity alone, then gravity: (v + h g) / (1 + h c / m)
  // would also shrink the kick that a resting cloth's constraints must undo, and leave it at
  // rest under the weight m g / (1 + h c / m).
  const double air =
      1.0 / (1.0 + h * m_system.cloth().params.damping_air / m_system.particle_mass());
  for (const int i : m_free) {
    v.segment<3>(3 * i) = air * v.segment<3>(3 * i) + gravity_kick;
    x.segment<3>(3 * i) += h * v.segment<3>(3 * i);
  }
  const ConstraintSet& constraints = m_system.constraints();
  for (const int i : constraints.fixed_particles())
    x.segment<3>(3 * i) = constraints.trajectory(i)->position(t_sub);
  m_lambda.setZero();
  m_contact_lambda.setZero();
  const double inv_h = 1.0 / h, inv_h2 = inv_h * inv_h;
  for (int k = 0; k < m_iterations; ++k)
    m_jacobi ? sweep_jacobi(inv_h2, inv_h) : sweep_gauss_seidel(inv_h2, inv_h);
  apply_friction();
  v = (x - m_previous) * inv_h;
}

void Xpbd::apply_friction() {
  const Collision& collision = m_system.collision();
  const double mu = collision.params().friction;
  if (mu == 0.0 || !m_system.dummy()) return;
  VecMap x = positions();
  for (const int i : m_free) {
    ContactConstraint c;
    if (m_contact_lambda[i] == 0.0 || !contact_constraint(collision, i, particle(x, i), c)) continue;
    const double length = c.gradient.norm();
    const double normal_move = m_inverse_mass[i] * std::abs(m_contact_lambda[i]) * length;
    const Vec3 previous = particle(m_previous, i);
    particle(x, i) = previous + coulomb_velocity_friction(particle(x, i) - previous,
                                                          c.gradient / length, normal_move, mu);
  }
}

bool Xpbd::spring_increment(Eigen::Index e, const double* x, double weight, double inv_h2,
                            double inv_h, double& increment, Vec3& u) const {
  if (weight == 0.0) return false;  // both ends fixed
  const Eigen::Index i = 3 * m_first[e], j = 3 * m_second[e];
  const Vec3 d(x[j] - x[i], x[j + 1] - x[i + 1], x[j + 2] - x[i + 2]);
  const double length = d.norm();
  if (length < degenerate_length) return false;  // no direction (docs/model.md section 4)
  u = d / length;
  const double* p = m_previous.data();
  const Vec3 motion(x[j] - p[j] - x[i] + p[i], x[j + 1] - p[j + 1] - x[i + 1] + p[i + 1],
                    x[j + 2] - p[j + 2] - x[i + 2] + p[i + 2]);
  increment = xpbd_multiplier_step(length - m_rest[e], weight, m_compliance[e] * inv_h2,
                                   m_lambda[e], m_damping_ratio[e] * inv_h, u.dot(motion));
  return true;
}

bool Xpbd::contact_increment(int i, const Vec3& x, double inverse_mass, double inv_h2,
                             double& increment, Vec3& gradient) const {
  ContactConstraint c;
  if (!contact_constraint(m_system.collision(), i, x, c)) return false;
  // lambda stays <= 0 (a push) without a clamp: from lambda <= 0 and C >= 0 the update gives
  // (lambda w |grad C|^2 - C) / (w |grad C|^2 + a) <= 0.
  const double compliance = inv_h2 / m_system.collision().params().stiffness;
  increment = xpbd_multiplier_step(c.value, inverse_mass * c.gradient.squaredNorm(),
                                   compliance, m_contact_lambda[i], 0.0, 0.0);
  gradient = c.gradient;
  return true;
}

void Xpbd::sweep(const double* x, double* target, const Eigen::ArrayXd& spring_weight,
                 const Eigen::ArrayXd& contact_weight, double inv_h2, double inv_h) {
  // A colour's springs share no particle, a contact is its particle's alone: each moves only
  // its own particles, so a colour, and the contacts, run on threads with the same bits.
  Eigen::Index colour_begin = 0;
  for (const Eigen::Index colour_end : m_colour_end) {
    parallel_for(colour_end - colour_begin, threaded_particles_from,
                 [&](std::ptrdiff_t begin, std::ptrdiff_t end) {
      double increment;
      Vec3 u;
      for (Eigen::Index e = colour_begin + begin; e < colour_begin + end; ++e) {
        if (!spring_increment(e, x, spring_weight[e], inv_h2, inv_h, increment, u)) continue;
        m_lambda[e] += increment;
        const Vec3 move_first = (m_w_first[e] * increment) * u;
        const Vec3 move_second = (m_w_second[e] * increment) * u;
        for (int a = 0; a < 3; ++a) {
          target[3 * m_first[e] + a] -= move_first[a];
          target[3 * m_second[e] + a] += move_second[a];
        }
      }
    });
    colour_begin = colour_end;
  }
  if (!m_system.dummy()) return;
  parallel_for(static_cast<std::ptrdiff_t>(m_free.size()), threaded_particles_from,
               [&](std::ptrdiff_t begin, std::ptrdiff_t end) {
    double increment;
    Vec3 u;
    for (std::ptrdiff_t k = begin; k < end; ++k) {
      const int i = m_free[static_cast<std::size_t>(k)];
      if (!contact_increment(i, Eigen::Map<const Vec3>(x + 3 * i), contact_weight[i], inv_h2,
                             increment, u))
        continue;
      m_contact_lambda[i] += increment;
      Eigen::Map<Vec3>(target + 3 * i) += (m_inverse_mass[i] * increment) * u;
    }
  });
}

void Xpbd::sweep_gauss_seidel(double inv_h2, double inv_h) {
  // Reads and writes the one iterate: each constraint sees its predecessors' moves.
  sweep(m_y.data(), m_y.data(), m_weight, m_inverse_mass, inv_h2, inv_h);
}

// Mass splitting (Tonge, Benevolenski and Voroshilov 2012, "Mass splitting for jitter-free
// parallel rigid body simulation"): each constraint sees a particle touched by n constraints as
// one of n copies of mass m / n, so its multiplier step has the weight sum n w |grad C|^2, and
// the particle moves by the copies' mean, w grad C dlambda per constraint (x and lambda move
// together, as XPBD needs). The weights dominate the rows of the constraint matrix, so the
// linearised iteration converges; where the compliance dominates (small substeps) the step is
// Gauss-Seidel's.
void Xpbd::sweep_jacobi(double inv_h2, double inv_h) {
  m_correction.setZero();
  sweep(m_y.data(), m_correction.data(), m_split_weight, m_split_inverse_mass, inv_h2, inv_h);
  positions() += m_correction;
}

IntegratorDeclaration xpbd_declaration() {
  return {"xpbd",
          "position-based",
          1,
          false,
          "XPBD with small steps (Macklin et al. 2016, 2019): springs and contacts as compliant "
          "constraints",
          own_keys,
          [](ClothSystem& system, const IntegratorOptions& options) -> std::unique_ptr<Integrator> {
            return std::make_unique<Xpbd>(system, options);
          }};
}

}  // namespace drape
