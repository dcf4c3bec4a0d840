#include "integrators/vbd/vertex_block_potential.hpp"

#include <cmath>

#include "core/forces/forces.hpp"

namespace drape {

namespace {

Vec3 at(const double* x, int i) { return Vec3(x[3 * i], x[3 * i + 1], x[3 * i + 2]); }

}  // namespace

VertexBlockPotential::VertexBlockPotential(const ClothSystem& system) : m_system(system) {
  const SpringList& springs = system.cloth().springs;
  const int n = system.num_particles();
  m_offsets.assign(static_cast<std::size_t>(n) + 1, 0);
  for (Eigen::Index e = 0; e < springs.size(); ++e) {
    ++m_offsets[static_cast<std::size_t>(springs.first[e]) + 1];
    ++m_offsets[static_cast<std::size_t>(springs.second[e]) + 1];
  }
  for (int i = 0; i < n; ++i) m_offsets[i + 1] += m_offsets[i];
  const std::size_t entries = static_cast<std::size_t>(m_offsets.back());
  m_spring.resize(entries);
  m_other.resize(entries);
  m_stiffness.resize(entries);
  m_rest.resize(entries);
  std::vector<int> fill(m_offsets.begin(), m_offsets.end() - 1);
  for (Eigen::Index e = 0; e < springs.size(); ++e) {
    for (const bool first : {true, false}) {
      const int i = first ? springs.first[e] : springs.second[e];
      const std::size_t k = static_cast<std::size_t>(fill[static_cast<std::size_t>(i)]++);
      m_spring[k] = static_cast<int>(e);
      m_other[k] = first ? springs.second[e] : springs.first[e];
      m_stiffness[k] = springs.stiffness[e];
      m_rest[k] = springs.rest[e];
    }
  }
  m_directions.assign(static_cast<std::size_t>(springs.size()), Vec3::Zero());
}

void VertexBlockPotential::begin_step(double h, ConstVecRef x_n, ConstVecRef v_n) {
  m_h = h;
  m_mass = m_system.particle_mass();
  m_c_spring = m_system.cloth().params.damping_spring;
  m_c_air = m_system.cloth().params.damping_air;
  m_weight = m_mass * m_system.params().gravity;
  m_x_n = x_n;
  m_y = x_n + h * v_n;
}

void VertexBlockPotential::freeze_directions(ConstVecRef x) {
  if (m_c_spring == 0.0) return;
  const SpringList& springs = m_system.cloth().springs;
  for (Eigen::Index e = 0; e < springs.size(); ++e) {
    const Vec3 d = particle(x, springs.second[e]) - particle(x, springs.first[e]);
    const double length = d.norm();
    // forces.hpp's damping force is zero on a degenerate spring: so is its dissipation.
    m_directions[static_cast<std::size_t>(e)] =
        length < degenerate_length ? Vec3::Zero() : Vec3(d / length);
  }
}

VertexBlock VertexBlockPotential::block(int i, const double* x, bool definite) const {
  const double inertia = m_mass / (m_h * m_h);
  const Vec3 xi = at(x, i);
  const Vec3 vi = (xi - at(m_x_n.data(), i)) / m_h;
  VertexBlock b;
  b.force = inertia * (at(m_y.data(), i) - xi) + m_weight - m_c_air * vi;
  b.hessian.diagonal().setConstant(inertia + m_c_air / m_h);
  for (int k = m_offsets[i]; k < m_offsets[i + 1]; ++k) {
    const int j = m_other[k];
    const Vec3 d = at(x, j) - xi;
    b.force += spring_force(d, m_stiffness[k], m_rest[k]);
    b.hessian += spring_jacobian(d, m_stiffness[k], m_rest[k], definite);
    if (m_c_spring == 0.0) continue;
    // The frozen u's sign does not matter: the force c (w . u) u and Hessian c u u^T / h are
    // even in u.
    const Vec3& u = m_directions[static_cast<std::size_t>(m_spring[k])];
    const Vec3 w = (at(x, j) - at(m_x_n.data(), j)) / m_h - vi;
    b.force += (m_c_spring * w.dot(u)) * u;
    b.hessian += (m_c_spring / m_h) * u * u.transpose();
  }
  const Collision& collision = m_system.collision();
  b.force += collision.force(i, xi);
  b.hessian -= collision.jacobian(i, xi, definite);
  const LaggedFriction& friction = m_system.friction();
  if (friction.frozen()) {
    b.force += friction.force(i, xi);
    b.hessian += friction.hessian(i, xi);  // positive semi-definite as it stands
  }
  return b;
}

double VertexBlockPotential::energy_change(int i, const double* x, const Vec3& dx,
                                           double& magnitude) const {
  const Vec3 xi = at(x, i);
  const Vec3 moved = xi + dx;
  const Vec3 xn = at(m_x_n.data(), i);
  double change = 0.0;
  magnitude = 0.0;
  const auto add = [&](double term) {
    change += term;
    magnitude += std::abs(term);
  };
  // |a + dx|^2 - |a|^2 = dx . (2 a + dx) for the inertia and air terms.
  add(m_mass / (2.0 * m_h * m_h) * dx.dot(xi + moved - 2.0 * at(m_y.data(), i)));
  add(-m_weight.dot(dx));
  add(m_c_air / (2.0 * m_h) * dx.dot(xi + moved - 2.0 * xn));
  const Vec3 vi = (xi - xn) / m_h;
  for (int k = m_offsets[i]; k < m_offsets[i + 1]; ++k) {
    const int j = m_other[k];
    const Vec3 d = at(x, j) - xi, d_moved = d - dx;
    const double length = d.norm(), moved_length = d_moved.norm();
    // L' - L = (L'^2 - L^2) / (L' + L) with L'^2 - L^2 = -dx . (d + d'): no cancellation.
    const double sum = length + moved_length;
    const double stretch = sum > 0.0 ? -dx.dot(d + d_moved) / sum : 0.0;
    add(0.5 * m_stiffness[k] * stretch * (sum - 2.0 * m_rest[k]));
    if (m_c_spring == 0.0) continue;
    const Vec3& u = m_directions[static_cast<std::size_t>(m_spring[k])];
    const double rate = ((at(x, j) - at(m_x_n.data(), j)) / m_h - vi).dot(u);
    const double rate_change = -dx.dot(u) / m_h;
    add(0.5 * m_h * m_c_spring * rate_change * (2.0 * rate + rate_change));
  }
  const Collision& collision = m_system.collision();
  double contact = collision.energy(i, moved), before = collision.energy(i, xi);
  const LaggedFriction& friction = m_system.friction();
  if (friction.frozen()) {
    contact += friction.energy(i, moved);
    before += friction.energy(i, xi);
  }
  magnitude += contact + before;
  return change + (contact - before);
}

double VertexBlockPotential::value(ConstVecRef x) const {
  double magnitude = 0.0;
  return value(x, magnitude);
}

double VertexBlockPotential::value(ConstVecRef x, double& magnitude) const {
  const auto& fixed = m_system.constraints().mask();
  const Collision& collision = m_system.collision();
  const LaggedFriction& friction = m_system.friction();
  double g = 0.0, gravity = 0.0;
  for (int i = 0; i < m_system.num_particles(); ++i) {
    if (fixed[static_cast<std::size_t>(i)]) continue;
    const Vec3 xi = particle(x, i);
    g += m_mass / (2.0 * m_h * m_h) * (xi - particle(m_y, i)).squaredNorm() +
         m_c_air / (2.0 * m_h) * (xi - particle(m_x_n, i)).squaredNorm() + collision.energy(i, xi);
    gravity -= m_weight.dot(xi);
    if (friction.frozen()) g += friction.energy(i, xi);
  }
  const SpringList& springs = m_system.cloth().springs;
  for (Eigen::Index e = 0; e < springs.size(); ++e) {
    const int i = springs.first[e], j = springs.second[e];
    g += spring_energy(particle(x, j) - particle(x, i), springs.stiffness[e], springs.rest[e]);
    const double rate =
        ((particle(x, j) - particle(m_x_n, j)) - (particle(x, i) - particle(m_x_n, i)))
            .dot(m_directions[static_cast<std::size_t>(e)]) /
        m_h;
    g += 0.5 * m_h * m_c_spring * rate * rate;
  }
  // Every term but gravity's is non-negative.
  magnitude = g + std::abs(gravity);
  return g + gravity;
}

}  // namespace drape
