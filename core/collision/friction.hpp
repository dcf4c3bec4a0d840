#pragma once
// Coulomb friction against the object (docs/model.md section 4.12), in the two forms the
// integrators take it:
//
// - The lagged, smoothed friction potential of IPC (Li et al. 2020, "Incremental Potential
//   Contact", ACM TOG 39(4), section 5; ipc-toolkit's smooth_friction_mollifier and
//   tangential potential): over a step of size h from x_start, each particle's normal force
//   magnitude lambda and tangent basis T (3x2, orthonormal, perpendicular to the contact force)
//   are frozen at x_start, u = T^T (x - x_start) is the step's tangential displacement and
//       D(x) = mu lambda f0(|u|),   f0(y) = y^2 / eps - y^3 / (3 eps^2) + eps / 3 (y < eps), y beyond,
//   with eps = epsilon_v h (epsilon_v: `collision.friction_epsilon`, a velocity). -grad D is a
//   force of magnitude mu lambda f1(|u|) opposing the tangential velocity u / h, f1 = f0' rising
//   from 0 to 1 as |u| / h reaches epsilon_v: Coulomb's law with its jump at zero velocity
//   smoothed. Its Hessian mu lambda T [f1/y (I - u u^T / y^2) + f1' u u^T / y^2] T^T has the
//   eigenvalues mu lambda f1(y) / y and mu lambda f1'(y), both >= 0: it is positive
//   semi-definite as it stands, the projection ipc-toolkit applies changes nothing.
// - The regularised Coulomb force of the current state (smooth_coulomb_force), for right-hand
//   sides of ODEs (the arkode-* integrators), with the same mollifier in velocity.
// - The velocity-level friction of Bridson, Fedkiw and Anderson 2002 ("Robust treatment of
//   collisions, contact and friction for cloth animation", SIGGRAPH, section 7.2): after a
//   velocity change dv_n along the normal, the tangential velocity v_t shrinks by
//   min(1, mu |dv_n| / |v_t|) (coulomb_velocity_friction); the same on displacements is the
//   position-based friction of Macklin et al. 2014 ("Unified particle physics for real-time
//   applications", ACM TOG 33(4), section 6.1).
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <vector>

#include "core/state/state.hpp"

namespace drape {

class Collision;

/// f0(y) of the smoothed friction potential (IPC eq. 14 with eps = epsilon_v h), y >= 0.
inline double friction_f0(double y, double eps) {
  if (y >= eps) return y;
  return y * y * (1.0 - y / (3.0 * eps)) / eps + eps / 3.0;
}

/// f1 = f0', the mollified Coulomb magnitude in [0, 1].
inline double friction_f1(double y, double eps) {
  if (y >= eps) return 1.0;
  const double r = y / eps;
  return r * (2.0 - r);
}

/// f1(y) / y, finite at y = 0 (2 / eps).
inline double friction_f1_over_y(double y, double eps) {
  if (y >= eps) return 1.0 / y;
  return (2.0 - y / eps) / eps;
}

/// f1'(y) = f0''(y) >= 0.
inline double friction_f1_slope(double y, double eps) {
  if (y >= eps) return 0.0;
  return 2.0 * (1.0 - y / eps) / eps;
}

/// Coulomb's bound on a tangential change (Bridson et al. 2002, section 7.2): `motion` (a
/// velocity, or a displacement for position-based friction) keeps its part along `normal` (a
/// unit vector) and its tangential part shrinks by mu |normal_change| / |tangential|, down to 0.
inline Vec3 coulomb_velocity_friction(const Vec3& motion, const Vec3& normal,
                                      double normal_change, double mu) {
  const Vec3 along = motion.dot(normal) * normal;
  const Vec3 tangential = motion - along;
  const double speed = tangential.norm();
  if (!(speed > 0.0)) return motion;
  return along + std::max(0.0, 1.0 - mu * std::abs(normal_change) / speed) * tangential;
}

/// The regularised Coulomb force of a particle at velocity v on which the object pushes with
/// `contact` (docs/friction.md, "Smooth Coulomb force"): with lambda = |contact|, n = contact /
/// lambda and v_t = v - (v . n) n,
///     F = -mu lambda f1(|v_t|, epsilon_v) v_t / |v_t|,
/// the lagged potential's force with the step's displacement over eps = epsilon_v h replaced by
/// the velocity over epsilon_v: the form of an ODE's right-hand side, which has no step start.
Vec3 smooth_coulomb_force(const Vec3& contact, const Vec3& v, double mu, double epsilon_v);
/// dF/dv of smooth_coulomb_force with lambda and n held (their dependence on x is left out):
/// -mu lambda [f1/y (P - t t^T) + f1'(y) t t^T], P = I - n n^T, y = |v_t|, t = v_t / y; a
/// symmetric negative semi-definite damping (-2 mu lambda / epsilon_v P at v_t = 0).
Mat3 smooth_coulomb_velocity_jacobian(const Vec3& contact, const Vec3& v, double mu,
                                      double epsilon_v);

/// The lagged friction potential of one step (IPC section 5): normal force magnitudes and
/// tangent bases frozen at the step's start, per cloth particle.
class LaggedFriction {
 public:
  /// `mu`: the friction coefficient; `epsilon`: the mollifier's width in velocity [m/s].
  LaggedFriction(double mu, double epsilon) : m_mu(mu), m_epsilon(epsilon) {}

  double coefficient() const { return m_mu; }
  double epsilon() const { return m_epsilon; }
  /// Whether a step's potential is frozen (between freeze and release).
  bool frozen() const { return m_frozen; }

  /// Freezes, for a step of size h from positions x_start (3N), each particle's normal force
  /// magnitude (|collision force| at x_start) and the tangent basis perpendicular to it.
  void freeze(const Collision& collision, ConstVecRef x_start, double h);
  /// Back to no friction potential.
  void release() { m_frozen = false; }

  /// D_i(x) of cloth particle i (0 without contact at the step's start).
  double energy(int i, const Vec3& x) const;
  /// -grad D_i(x): the friction force on particle i.
  Vec3 force(int i, const Vec3& x) const;
  /// The Hessian of D_i at x (positive semi-definite).
  Mat3 hessian(int i, const Vec3& x) const;
  /// The frozen normal force magnitude of particle i.
  double normal_force(int i) const { return m_normal_force[static_cast<std::size_t>(i)]; }

 private:
  /// u = T^T (x - x_start) of particle i.
  Eigen::Vector2d tangential(int i, const Vec3& x) const;
  Eigen::Matrix<double, 3, 2> basis(int i) const;

  double m_mu, m_epsilon;
  double m_eps = 0.0;  // epsilon_v h: the mollifier's width in displacement
  bool m_frozen = false;
  std::vector<double> m_normal_force;  // N: mu-less lambda
  std::vector<double> m_basis;         // N x 6: the two tangent vectors
  Eigen::VectorXd m_start;             // 3N
};

}  // namespace drape
