#include "integrators/newton/incremental_potential.hpp"

#include <array>
#include <cmath>

#include "core/forces/forces.hpp"
#include "core/parallel/fixed_block_sum.hpp"

namespace drape {

IncrementalPotential::IncrementalPotential(const ClothSystem& system, ForceSplit split)
    : m_system(system), m_split(split) {}

void IncrementalPotential::begin_stage(double t, double gamma, ConstVecRef a, VecRef z) {
  m_t = t;
  m_gamma = gamma;
  m_a = a;
  // The fixed rows of f_I are the prescribed motion, whatever z: one evaluation gives them.
  m_fixed_rhs.resize(a.size());
  m_system.rhs(t, z, m_fixed_rhs, m_split);
  const Eigen::Index n3 = a.size() / 2;
  for (const int i : m_system.constraints().fixed_particles()) {
    particle(z.head(n3), i) = particle(a.head(n3), i) + gamma * particle(m_fixed_rhs.head(n3), i);
    particle(z.tail(n3), i) = particle(a.tail(n3), i) + gamma * particle(m_fixed_rhs.tail(n3), i);
  }
  state_of(Eigen::VectorXd(z.tail(n3)), z);
  freeze_damping(z);
}

void IncrementalPotential::freeze_damping(ConstVecRef z) {
  const SpringList& springs = m_system.cloth().springs;
  const auto x = z.head(z.size() / 2);
  m_directions.resize(static_cast<std::size_t>(springs.size()));
  parallel_for(springs.size(), threaded_particles_from,
               [&](std::ptrdiff_t begin, std::ptrdiff_t end) {
                 for (Eigen::Index e = begin; e < end; ++e) {
                   const Vec3 d = particle(x, springs.second[e]) - particle(x, springs.first[e]);
                   const double length = d.norm();
                   // The damping force of forces.hpp is zero on a degenerate spring: so is its
                   // dissipation.
                   m_directions[static_cast<std::size_t>(e)] =
                       length < degenerate_length ? Vec3::Zero() : Vec3(d / length);
                 }
               });
  m_contacts.clear();
  if (!m_split.with_smooth_friction || !m_system.dummy() ||
      m_system.friction().coefficient() == 0.0)
    return;
  m_contacts.resize(static_cast<std::size_t>(m_system.num_particles()));
  for (int i = 0; i < m_system.num_particles(); ++i)
    m_contacts[static_cast<std::size_t>(i)] = m_system.collision().force(i, particle(x, i));
}

double IncrementalPotential::friction_dissipation(ConstVecRef v) const {
  const auto& fixed = m_system.constraints().mask();
  const double mu = m_system.friction().coefficient(), epsilon_v = m_system.friction().epsilon();
  double sum = 0.0;
  for (std::size_t i = 0; i < m_contacts.size(); ++i) {
    const double lambda = m_contacts[i].norm();
    if (fixed[i] || !(lambda > 0.0)) continue;
    const Vec3 normal = m_contacts[i] / lambda;
    const Vec3 vi = particle(v, static_cast<Eigen::Index>(i));
    sum += mu * lambda * friction_f0((vi - vi.dot(normal) * normal).norm(), epsilon_v);
  }
  return sum;
}

void IncrementalPotential::state_of(ConstVecRef v, VecRef z) const {
  const Eigen::Index n3 = z.size() / 2;
  const auto& fixed = m_system.constraints().mask();
  parallel_for(n3 / 3, threaded_particles_from, [&](std::ptrdiff_t begin, std::ptrdiff_t end) {
    for (Eigen::Index i = begin; i < end; ++i) {
      if (fixed[static_cast<std::size_t>(i)]) continue;
      particle(z.tail(n3), i) = particle(v, i);
      particle(z.head(n3), i) = particle(m_a.head(n3), i) + m_gamma * particle(v, i);
    }
  });
}

double IncrementalPotential::value(ConstVecRef z) const {
  double magnitude = 0.0;
  return value(z, magnitude);
}

double IncrementalPotential::value(ConstVecRef z, double& magnitude) const {
  const Eigen::Index n3 = z.size() / 2;
  const auto x = z.head(n3), v = z.tail(n3);
  const auto& fixed = m_system.constraints().mask();
  const double mass = m_system.particle_mass();
  // The sums over particles and springs are fixed-block sums (core/parallel): the same bits on
  // any number of threads.
  const auto [inertia, air] = fixed_block_sums<2>(
      n3 / 3, particles_per_block, [&](std::ptrdiff_t begin, std::ptrdiff_t end) {
        std::array<double, 2> sums{0.0, 0.0};
        for (Eigen::Index i = begin; i < end; ++i) {
          if (fixed[static_cast<std::size_t>(i)]) continue;
          sums[0] += (particle(v, i) - particle(m_a.tail(n3), i)).squaredNorm();
          sums[1] += particle(v, i).squaredNorm();
        }
        return sums;
      });
  const EnergyBreakdown u = m_system.energy(x, v);
  double e = 0.5 * mass * inertia;
  magnitude = e;
  if (m_split.with_springs) {
    e += u.spring;
    magnitude += u.spring;
    const SpringList& springs = m_system.cloth().springs;
    const double c = m_system.cloth().params.damping_spring;
    double dissipation = 0.0;
    if (c > 0.0)
      dissipation = fixed_block_sum(
          springs.size(), springs_per_block, [&](std::ptrdiff_t begin, std::ptrdiff_t end) {
            double sum = 0.0;
            for (Eigen::Index s = begin; s < end; ++s) {
              const double rate = (particle(v, springs.second[s]) - particle(v, springs.first[s]))
                                      .dot(m_directions[static_cast<std::size_t>(s)]);
              sum += rate * rate;
            }
            return sum;
          });
    e += m_gamma * 0.5 * c * dissipation;
    magnitude += m_gamma * 0.5 * c * dissipation;
  }
  // Air damping on fixed particles is no function of the unknowns: left out like their inertia.
  if (m_split.with_collision) {
    e += u.collision + u.friction;
    magnitude += u.collision + u.friction;
  }
  if (!m_contacts.empty()) {
    const double dissipation = m_gamma * friction_dissipation(v);
    e += dissipation;
    magnitude += dissipation;
  }
  if (m_split.with_body) {
    const double dissipation = m_gamma * 0.5 * m_system.cloth().params.damping_air * air;
    e += u.gravity + dissipation;
    magnitude += std::abs(u.gravity) + dissipation;
  }
  return e;
}

void IncrementalPotential::gradient(ConstVecRef z, VecRef g) const {
  const Eigen::Index n3 = z.size() / 2;
  m_force.resize(n3);
  m_system.forces(z.head(n3), z.tail(n3), m_force, m_split);
  g = m_system.particle_mass() * (z.tail(n3) - m_a.tail(n3)) - m_gamma * m_force;
  m_system.constraints().zero_fixed(g);
}

}  // namespace drape
