#include "core/collision/friction.hpp"

#include <Eigen/Geometry>
#include <cmath>

#include "core/collision/collision.hpp"

namespace drape {

Vec3 smooth_coulomb_force(const Vec3& contact, const Vec3& v, double mu, double epsilon_v) {
  const double lambda = contact.norm();
  if (!(lambda > 0.0)) return Vec3::Zero();
  const Vec3 normal = contact / lambda;
  const Vec3 tangential = v - v.dot(normal) * normal;
  return -(mu * lambda * friction_f1_over_y(tangential.norm(), epsilon_v)) * tangential;
}

Mat3 smooth_coulomb_velocity_jacobian(const Vec3& contact, const Vec3& v, double mu,
                                      double epsilon_v) {
  const double lambda = contact.norm();
  if (!(lambda > 0.0)) return Mat3::Zero();
  const Vec3 normal = contact / lambda;
  const Vec3 tangential = v - v.dot(normal) * normal;
  const double y = tangential.norm();
  const double across = friction_f1_over_y(y, epsilon_v);
  // In the tangent plane: f1/y across v_t and f1' along it; nothing along the normal.
  Mat3 jacobian = across * (Mat3::Identity() - normal * normal.transpose());
  if (y > 0.0) {
    const Vec3 along = tangential / y;
    jacobian += (friction_f1_slope(y, epsilon_v) - across) * along * along.transpose();
  }
  return -mu * lambda * jacobian;
}

void LaggedFriction::freeze(const Collision& collision, ConstVecRef x_start, double h) {
  const auto n = static_cast<std::size_t>(x_start.size() / 3);
  m_eps = m_epsilon * h;
  m_start = x_start;
  m_normal_force.assign(n, 0.0);
  m_basis.assign(6 * n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 f = collision.force(static_cast<int>(i), particle(x_start, static_cast<Eigen::Index>(i)));
    const double lambda = f.norm();
    if (!(lambda > 0.0)) continue;
    const Vec3 normal = f / lambda;
    // Any orthonormal pair perpendicular to the normal: D depends on |u| only. Crossed with the
    // coordinate axis least aligned with the normal, so that the cross product is never small.
    Eigen::Index axis;
    normal.cwiseAbs().minCoeff(&axis);
    const Vec3 first = normal.cross(Vec3::Unit(axis)).normalized();
    const Vec3 second = normal.cross(first);
    m_normal_force[i] = lambda;
    std::copy(first.data(), first.data() + 3, m_basis.begin() + 6 * i);
    std::copy(second.data(), second.data() + 3, m_basis.begin() + 6 * i + 3);
  }
  m_frozen = true;
}

Eigen::Matrix<double, 3, 2> LaggedFriction::basis(int i) const {
  return Eigen::Map<const Eigen::Matrix<double, 3, 2>>(m_basis.data() + 6 * i);
}

Eigen::Vector2d LaggedFriction::tangential(int i, const Vec3& x) const {
  return basis(i).transpose() * (x - particle(m_start, i));
}

double LaggedFriction::energy(int i, const Vec3& x) const {
  const double lambda = m_normal_force[static_cast<std::size_t>(i)];
  if (lambda == 0.0) return 0.0;
  return m_mu * lambda * friction_f0(tangential(i, x).norm(), m_eps);
}

Vec3 LaggedFriction::force(int i, const Vec3& x) const {
  const double lambda = m_normal_force[static_cast<std::size_t>(i)];
  if (lambda == 0.0) return Vec3::Zero();
  const Eigen::Vector2d u = tangential(i, x);
  return -(m_mu * lambda * friction_f1_over_y(u.norm(), m_eps)) * (basis(i) * u);
}

Mat3 LaggedFriction::hessian(int i, const Vec3& x) const {
  const double lambda = m_normal_force[static_cast<std::size_t>(i)];
  if (lambda == 0.0) return Mat3::Zero();
  const Eigen::Vector2d u = tangential(i, x);
  const double y = u.norm();
  const double across = friction_f1_over_y(y, m_eps);
  // In the tangent plane: f1/y across u and f1' along it; at u = 0 both are 2 / eps.
  Eigen::Matrix2d in_plane = across * Eigen::Matrix2d::Identity();
  if (y > 0.0) {
    const Eigen::Vector2d along = u / y;
    in_plane += (friction_f1_slope(y, m_eps) - across) * along * along.transpose();
  }
  const Eigen::Matrix<double, 3, 2> t = basis(i);
  return m_mu * lambda * t * in_plane * t.transpose();
}

}  // namespace drape
