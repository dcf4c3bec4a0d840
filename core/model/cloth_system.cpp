#include "core/model/cloth_system.hpp"

#include <algorithm>
#include <atomic>
#include <optional>
#include <vector>

#include "core/forces/forces.hpp"
#include "core/parallel/parallel_for.hpp"

namespace drape {

ClothSystem::ClothSystem(Cloth cloth, std::shared_ptr<const Dummy> dummy, ForceParams params)
    : m_cloth(std::move(cloth)),
      m_dummy(std::move(dummy)),
      m_collision(m_dummy, params.collision, m_cloth.size()),
      m_friction(params.collision.friction, params.collision.friction_epsilon),
      m_spring_forces(m_cloth),
      m_params(params),
      m_constraints(m_cloth.size()) {}

Eigen::VectorXd ClothSystem::initial_state(double t) const {
  Eigen::VectorXd y = Eigen::VectorXd::Zero(size());
  const Eigen::Index n3 = 3 * num_particles();
  y.head(n3) = m_cloth.rest_positions;
  m_constraints.project(t, VecMap(y.data(), n3), VecMap(y.data() + n3, n3));
  return y;
}

void ClothSystem::forces(ConstVecRef x, ConstVecRef v, VecRef f) const {
  forces(x, v, f, ForceSplit::all);
}

void ClothSystem::forces(ConstVecRef x, ConstVecRef v, VecRef f, ForceSplit split) const {
  evaluate_forces<false>(x, v, f, split);
}

template <bool per_mass>
void ClothSystem::evaluate_forces(ConstVecRef x, ConstVecRef v, VecRef f, ForceSplit split) const {
  const bool with_springs = split.with_springs;
  const bool with_body = split.with_body;
  const double c_air = m_cloth.params.damping_air;
  const double m = particle_mass();
  const Vec3 weight = m * m_params.gravity;
  const bool with_collision = m_dummy && split.with_collision;
  const bool with_friction = with_collision && m_friction.frozen();
  const bool with_smooth_friction = smooth_friction(split);
  const double mu = m_friction.coefficient(), epsilon_v = m_friction.epsilon();
  std::optional<ConstComponents> springs;
  if (with_springs) springs.emplace(m_spring_forces.evaluate(x, v, m_cloth.params.damping_spring));

  // One pass over particles gathers the terms and divides by the mass (a separate pass over 3N
  // values would cost as much again), adding in registers and storing each particle once.
  parallel_for(num_particles(), threaded_particles_from, [&](std::ptrdiff_t begin, std::ptrdiff_t end) {
    for (auto i = static_cast<int>(begin); i < end; ++i) {
      Vec3 total = Vec3::Zero();
      if (springs) total = Vec3((*springs)(i, 0), (*springs)(i, 1), (*springs)(i, 2));
      if (with_body) total += weight - c_air * particle(v, i);
      if (with_collision || with_smooth_friction) {
        const Vec3 contact = m_collision.force(i, particle(x, i));
        if (with_collision) total += contact;
        if (with_smooth_friction)
          total += smooth_coulomb_force(contact, particle(v, i), mu, epsilon_v);
      }
      if (with_friction) total += m_friction.force(i, particle(x, i));
      if constexpr (per_mass) total /= m;
      particle(f, i) = total;
    }
  });
}

void ClothSystem::acceleration(double t, ConstVecRef x, ConstVecRef v,
                               VecRef a) const {
  evaluate_forces<true>(x, v, a, ForceSplit::all);
  for (const int i : m_constraints.fixed_particles())
    particle(a, i) = m_constraints.trajectory(i)->acceleration(t);
}

void ClothSystem::rhs(double t, ConstVecRef y, VecRef y_dot) const {
  rhs(t, y, y_dot, ForceSplit::all);
}

void ClothSystem::rhs(double t, ConstVecRef y, VecRef y_dot, ForceSplit split) const {
  const Eigen::Index n3 = 3 * num_particles();
  const ConstVecMap x(y.data(), n3), v(y.data() + n3, n3);
  VecMap x_dot(y_dot.data(), n3), v_dot(y_dot.data() + n3, n3);
  evaluate_forces<true>(x, v, v_dot, split);
  if (!split.with_kinematics) {
    x_dot.setZero();
    m_constraints.zero_fixed(v_dot);
    return;
  }
  x_dot = v;
  m_constraints.apply_to_rhs(t, x_dot, v_dot);
}

void ClothSystem::freeze_friction(ConstVecRef x, double h) {
  if (m_dummy && m_friction.coefficient() > 0.0) m_friction.freeze(m_collision, x, h);
}

void ClothSystem::apply_velocity_friction(ConstVecRef x, VecRef v, double dt) const {
  const double mu = m_friction.coefficient();
  if (!m_dummy || mu == 0.0) return;
  const auto& fixed = m_constraints.mask();
  const double per_mass = dt / particle_mass();
  for (int i = 0; i < num_particles(); ++i) {
    if (fixed[static_cast<std::size_t>(i)]) continue;
    const Vec3 f = m_collision.force(i, particle(x, i));
    const double magnitude = f.norm();
    if (!(magnitude > 0.0)) continue;
    particle(v, i) = coulomb_velocity_friction(particle(v, i), f / magnitude, per_mass * magnitude, mu);
  }
}

int ClothSystem::project(double t, VecRef x, VecRef v) const {
  // A count, added up exactly in any order.
  std::atomic<int> corrected{0};
  if (m_dummy) {
    const auto& fixed = m_constraints.mask();
    parallel_for(num_particles(), threaded_particles_from, [&](std::ptrdiff_t begin, std::ptrdiff_t end) {
      int block_corrected = 0;
      for (auto i = static_cast<int>(begin); i < end; ++i) {
        if (fixed[i]) continue;
        Vec3 xi = particle(x, i), vi = particle(v, i);
        if (!m_collision.correct_penetration(i, xi, vi)) continue;
        particle(x, i) = xi;
        particle(v, i) = vi;
        ++block_corrected;
      }
      corrected += block_corrected;
    });
  }
  m_constraints.project(t, x, v);
  return corrected;
}

EnergyBreakdown ClothSystem::energy(ConstVecRef x, ConstVecRef v) const {
  EnergyBreakdown e;
  const double m = particle_mass();
  e.kinetic = 0.5 * m * v.squaredNorm();
  const SpringList& springs = m_cloth.springs;
  for (Eigen::Index s = 0; s < springs.size(); ++s)
    e.spring += spring_energy(particle(x, springs.second[s]) - particle(x, springs.first[s]),
                              springs.stiffness[s], springs.rest[s]);
  for (int i = 0; i < num_particles(); ++i) e.gravity -= m * m_params.gravity.dot(particle(x, i));
  for (int i = 0; m_dummy && i < num_particles(); ++i)
    e.collision += m_collision.energy(i, particle(x, i));
  for (int i = 0; m_friction.frozen() && i < num_particles(); ++i)
    e.friction += m_friction.energy(i, particle(x, i));
  return e;
}

void ClothSystem::spring_jacobian_block(ConstVecRef x, ConstVecRef v, bool definite,
                                        Eigen::Index e, Mat3& jx, Mat3& jv) const {
  const SpringList& springs = m_cloth.springs;
  const double c_spring = m_cloth.params.damping_spring;
  const int i = springs.first[e], j = springs.second[e];
  const Vec3 d = particle(x, j) - particle(x, i);
  jx = spring_jacobian(d, springs.stiffness[e], springs.rest[e], definite);
  jv = Mat3::Zero();
  if (c_spring > 0.0) {
    jv = damping_velocity_jacobian(d, c_spring);
    // The damping's dependence on x is not symmetric; a definite (SPD) request leaves it out.
    if (!definite) jx += damping_position_jacobian(d, particle(v, j) - particle(v, i), c_spring);
  }
}

Mat3 ClothSystem::particle_position_jacobian(ConstVecRef x, bool definite, ForceSplit split,
                                             int i) const {
  Mat3 contact = Mat3::Zero();
  if (split.with_collision) contact = m_collision.jacobian(i, particle(x, i), definite);
  // The friction Hessian is positive semi-definite (friction.hpp): definite either way.
  if (split.with_collision && m_friction.frozen()) contact -= m_friction.hessian(i, particle(x, i));
  return contact;
}

Mat3 ClothSystem::air_jacobian(ForceSplit split) const {
  return split.with_body ? Mat3(-m_cloth.params.damping_air * Mat3::Identity()) : Mat3::Zero();
}

bool ClothSystem::smooth_friction(ForceSplit split) const {
  return split.with_smooth_friction && m_dummy && m_friction.coefficient() > 0.0;
}

Mat3 ClothSystem::particle_velocity_jacobian(ConstVecRef x, ConstVecRef v, ForceSplit split,
                                             int i, const Mat3& air) const {
  if (!smooth_friction(split)) return air;
  return air + smooth_coulomb_velocity_jacobian(m_collision.force(i, particle(x, i)),
                                                particle(v, i), m_friction.coefficient(),
                                                m_friction.epsilon());
}

// Calls visit(i, j, Jx, Jv) for every pair block: j >= 0 for springs (the pair pattern of
// forces.hpp), j < 0 for a block acting on particle i alone (dF_i/dx_i, dF_i/dv_i).
template <class Visit>
void ClothSystem::for_each_jacobian_block(ConstVecRef x, ConstVecRef v, bool definite,
                                          ForceSplit split, Visit&& visit) const {
  const SpringList& springs = m_cloth.springs;
  Mat3 jx, jv;
  for (Eigen::Index e = 0; split.with_springs && e < springs.size(); ++e) {
    spring_jacobian_block(x, v, definite, e, jx, jv);
    visit(springs.first[e], springs.second[e], jx, jv);
  }
  if (!split.with_collision && !split.with_body && !smooth_friction(split)) return;
  const Mat3 air = air_jacobian(split);
  for (int i = 0; i < num_particles(); ++i)
    visit(i, -1, particle_position_jacobian(x, definite, split, i),
          particle_velocity_jacobian(x, v, split, i, air));
}

void ClothSystem::force_jacobian_times(ConstVecRef x, ConstVecRef v,
                                       ConstVecRef dx, ConstVecRef dv, VecRef out,
                                       bool definite) const {
  force_jacobian_times(x, v, dx, dv, out, definite, ForceSplit::all);
}

void ClothSystem::force_jacobian_times(ConstVecRef x, ConstVecRef v, ConstVecRef dx,
                                       ConstVecRef dv, VecRef out, bool definite,
                                       ForceSplit split) const {
  out.setZero();
  for_each_jacobian_block(x, v, definite, split, [&](int i, int j, const Mat3& jx, const Mat3& jv) {
    if (j < 0) {
      particle(out, i) += jx * particle(dx, i) + jv * particle(dv, i);
      return;
    }
    const Vec3 df = jx * (particle(dx, j) - particle(dx, i)) + jv * (particle(dv, j) - particle(dv, i));
    particle(out, i) += df;
    particle(out, j) -= df;
  });
  m_constraints.zero_fixed(out);
}

void ClothSystem::force_jacobians(ConstVecRef x, ConstVecRef v, bool definite,
                                  Eigen::SparseMatrix<double>& dfdx,
                                  Eigen::SparseMatrix<double>& dfdv) const {
  force_jacobians(x, v, definite, dfdx, dfdv, ForceSplit::all);
}

void ClothSystem::force_jacobians(ConstVecRef x, ConstVecRef v, bool definite,
                                  Eigen::SparseMatrix<double>& dfdx,
                                  Eigen::SparseMatrix<double>& dfdv, ForceSplit split) const {
  using Triplet = Eigen::Triplet<double>;
  std::vector<Triplet> tx, tv;
  const auto& fixed = m_constraints.mask();
  auto add_block = [&](std::vector<Triplet>& t, int row, int col, const Mat3& block) {
    if (fixed[row]) return;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        if (block(a, b) != 0.0) t.emplace_back(3 * row + a, 3 * col + b, block(a, b));
  };
  auto add_pair = [&](std::vector<Triplet>& t, int i, int j, const Mat3& block) {
    add_block(t, i, i, -block);
    add_block(t, i, j, block);
    add_block(t, j, i, block);
    add_block(t, j, j, -block);
  };
  for_each_jacobian_block(x, v, definite, split, [&](int i, int j, const Mat3& jx, const Mat3& jv) {
    if (j < 0) {
      add_block(tx, i, i, jx);
      add_block(tv, i, i, jv);
    } else {
      add_pair(tx, i, j, jx);
      add_pair(tv, i, j, jv);
    }
  });
  const Eigen::Index n3 = 3 * num_particles();
  dfdx.resize(n3, n3);
  dfdv.resize(n3, n3);
  dfdx.setFromTriplets(tx.begin(), tx.end());
  dfdv.setFromTriplets(tv.begin(), tv.end());
}

void ClothSystem::force_jacobian_blocks(ConstVecRef x, ConstVecRef v, bool definite,
                                        ForceSplit split, JacobianBlocks& blocks) const {
  const auto springs = static_cast<std::size_t>(m_cloth.springs.size());
  const auto particles = static_cast<std::size_t>(num_particles());
  // Every block is written once, by the thread of its spring or particle.
  blocks.spring_x.resize(springs);
  blocks.spring_v.resize(springs);
  blocks.particle_x.resize(particles);
  blocks.particle_v.resize(particles);
  parallel_for(m_cloth.springs.size(), threaded_particles_from,
               [&](std::ptrdiff_t begin, std::ptrdiff_t end) {
                 for (auto e = static_cast<std::size_t>(begin); e < static_cast<std::size_t>(end);
                      ++e) {
                   if (split.with_springs) {
                     spring_jacobian_block(x, v, definite, static_cast<Eigen::Index>(e),
                                           blocks.spring_x[e], blocks.spring_v[e]);
                   } else {
                     blocks.spring_x[e].setZero();
                     blocks.spring_v[e].setZero();
                   }
                 }
               });
  const bool with_particles = split.with_collision || split.with_body || smooth_friction(split);
  const Mat3 air = air_jacobian(split);
  parallel_for(num_particles(), threaded_particles_from,
               [&](std::ptrdiff_t begin, std::ptrdiff_t end) {
                 for (auto i = static_cast<int>(begin); i < end; ++i) {
                   const auto k = static_cast<std::size_t>(i);
                   blocks.particle_x[k] = with_particles
                                              ? particle_position_jacobian(x, definite, split, i)
                                              : Mat3::Zero();
                   blocks.particle_v[k] = with_particles
                                              ? particle_velocity_jacobian(x, v, split, i, air)
                                              : Mat3::Zero();
                 }
               });
}

}  // namespace drape
