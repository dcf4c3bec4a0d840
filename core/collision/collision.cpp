#include "core/collision/collision.hpp"

#include <cmath>
#include <vector>

#include "core/collision/smooth_contact.hpp"
#include "core/forces/forces.hpp"

namespace drape {

Collision::Collision(std::shared_ptr<const Dummy> dummy, const CollisionParams& params,
                     int num_particles)
    : m_dummy(std::move(dummy)),
      m_params(params),
      m_contacts(m_dummy, params.threshold, m_dummy ? num_particles : 0),
      m_outside_anchor(Eigen::VectorXd::Zero(m_dummy ? 3 * num_particles : 0)),
      m_outside_margin2(Eigen::VectorXd::Constant(m_dummy ? num_particles : 0, -1.0)) {
  if (m_dummy && params.model == CollisionModel::smooth) m_smooth.emplace(m_dummy->sections());
}

Vec3 Collision::smooth_force(const Vec3& x) const {
  const SmoothGap g = m_smooth->gap(x);
  return -smooth_contact_slope(g.gap, m_params.stiffness, m_params.threshold) * g.gradient;
}

// Newton's method on G along its gradient: radial on the sides, vertical at the end planes.
// A few steps reach G = 0 to round-off from the shallow penetrations a step leaves.
bool Collision::correct_smooth_penetration(Vec3& x, Vec3& v) const {
  SmoothGap g = m_smooth->gap(x);
  if (g.gap >= 0.0) return false;
  for (int iteration = 0; iteration < 8 && g.gap < 0.0; ++iteration) {
    const double norm2 = g.gradient.squaredNorm();
    if (!(norm2 > 0.0)) break;
    x -= (g.gap / norm2) * g.gradient;
    g = m_smooth->gap(x);
  }
  const Vec3 normal = g.gradient.normalized();
  const double inward = v.dot(normal);
  if (inward < 0.0) v -= inward * normal;
  return true;
}

Vec3 Collision::surface_force(const Vec3& x) const {
  const double delta = m_params.threshold, k = m_params.stiffness;
  const auto g = m_dummy->surface_gap(x);
  return g && g->gap < delta ? Vec3(k * (delta - g->gap) * g->gradient) : Vec3::Zero();
}

double Collision::energy(int i, const Vec3& x) const {
  if (!m_dummy) return 0.0;
  const double delta = m_params.threshold, k = m_params.stiffness;
  if (!m_planes.empty()) {
    const std::optional<double> g = plane_gap(i, x);
    return g && *g < delta ? 0.5 * k * (delta - *g) * (delta - *g) : 0.0;
  }
  if (m_params.model == CollisionModel::surface) {
    const auto g = m_dummy->surface_gap(x);
    return g && g->gap < delta ? 0.5 * k * (delta - g->gap) * (delta - g->gap) : 0.0;
  }
  if (m_smooth) return smooth_contact_energy(m_smooth->gap(x).gap, k, delta);
  const NearestObjectParticle hit = m_contacts.nearest(i, x);
  return hit.index < 0 ? 0.0 : collision_energy(x - m_dummy->position(hit.index), k, delta);
}

Mat3 Collision::jacobian(int i, const Vec3& x, bool definite) const {
  if (!m_dummy) return Mat3::Zero();
  const double delta = m_params.threshold, k = m_params.stiffness;
  if (!m_planes.empty()) {
    const std::optional<double> g = plane_gap(i, x);
    if (!g || *g >= delta) return Mat3::Zero();
    const Vec3& n = m_planes[static_cast<std::size_t>(i)].gradient;
    return -k * n * n.transpose();
  }
  if (m_params.model == CollisionModel::surface) {
    const auto g = m_dummy->surface_gap(x);
    if (!g || g->gap >= delta) return Mat3::Zero();
    return -k * g->gradient * g->gradient.transpose();
  }
  if (m_smooth) {
    // Hessian of E(G(x)): E'' grad G grad G^T + E' Hess G; the second term is indefinite
    // wherever the surface curves, hence the projection for the definite Jacobian.
    const SmoothGap g = m_smooth->gap(x);
    if (g.gap >= delta) return Mat3::Zero();
    const Mat3 hessian = smooth_contact_curvature(g.gap, k, delta) * g.gradient * g.gradient.transpose() +
                         smooth_contact_slope(g.gap, k, delta) * g.hessian;
    return -(definite ? project_to_psd(hessian) : hessian);
  }
  const NearestObjectParticle hit = m_contacts.nearest(i, x);
  if (hit.index < 0) return Mat3::Zero();
  return collision_jacobian(x - m_dummy->position(hit.index), k, delta, definite);
}

void Collision::pair_contacts(ConstVecRef x) {
  if (!m_dummy || m_smooth) return;
  m_planes.resize(static_cast<std::size_t>(x.size() / 3));
  for (std::size_t i = 0; i < m_planes.size(); ++i) {
    const Vec3 xi = particle(x, static_cast<Eigen::Index>(i));
    m_planes[i] = m_params.model == CollisionModel::particle ? particle_plane(xi) : surface_plane(xi);
  }
}

// Both planes reach twice the threshold: a particle that starts a step outside delta but
// reaches it during the step is repelled too (the force is zero until then), unless it moves
// delta in one step.
Collision::ContactPlane Collision::particle_plane(const Vec3& x) const {
  const NearestObjectParticle hit = m_dummy->nearest_within(x, 2.0 * m_params.threshold);
  if (hit.index < 0) return {};
  const Vec3 d = x - m_dummy->position(hit.index);
  // On the object particle (a corrected penetration puts it there) the force of docs/model.md section 4.5 pushes along
  // the object particle's normal, as if from a gap of 0.
  if (hit.distance < degenerate_length) {
    const Vec3 normal = m_dummy->normal(hit.index);
    return {x, 0.0, normal, normal, 1.0, hit.index, true};
  }
  return {x, hit.distance, d / hit.distance, d, hit.distance, hit.index, true};
}

Collision::ContactPlane Collision::surface_plane(const Vec3& x) const {
  const auto g = m_dummy->surface_gap(x);
  if (!g || g->gap >= 2.0 * m_params.threshold) return {};
  return {x, g->gap, g->gradient, g->gradient, 1.0, -1, true};
}

// A particle that has left its outside margin: a new margin, or the exact test.
bool Collision::correct_penetration_off_margin(int i, Vec3& x, Vec3& v) const {
  const double margin = m_dummy->outside_margin(x);
  if (margin > 0.0) {
    m_outside_anchor.segment<3>(3 * i) = x;
    m_outside_margin2[i] = margin * margin;
    return false;
  }
  Vec3 normal;
  if (m_params.model == CollisionModel::surface) {
    const auto g = m_dummy->surface_gap(x);
    if (!g || g->gap >= 0.0) return false;
    // Radially out by the gap: theta and y are unchanged, so the gap becomes exactly 0.
    const Eigen::Vector2d axis = m_dummy->axis_at(x.y());
    const Vec3 radial = Vec3(x.x() - axis.x(), 0.0, x.z() - axis.y()).normalized();
    x -= g->gap * radial;
    // The normal where the particle now is: the gradient's tangential part scales with 1/r_h.
    normal = m_dummy->surface_gap(x)->gradient.normalized();
  } else {
    if (!m_dummy->inside(x)) return false;
    const int o = m_dummy->nearest(x).index;
    x = m_dummy->position(o);
    normal = m_dummy->normal(o);
  }
  const double inward = v.dot(normal);
  if (inward < 0.0) v -= inward * normal;
  return true;
}

}  // namespace drape
