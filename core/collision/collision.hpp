#pragma once
// The collision of the cloth with the object (the paper's section 2.3 and the extensions of
// docs/model.md section 4): per cloth particle, the nearest object particle within the
// threshold delta (ContactFinder, core/dummy/contact_finder.hpp), the surface gap or the smooth
// potential, paired or not, and the penetration correction.
#include <memory>
#include <optional>
#include <vector>

#include "core/dummy/contact_finder.hpp"
#include "core/dummy/dummy.hpp"
#include "core/dummy/smooth_surface.hpp"
#include "core/forces/forces.hpp"

namespace drape {

/// How the cloth feels the object (docs/model.md section 4).
enum class CollisionModel {
  particle,  ///< the paper's: repulsion from the nearest object particle
  surface,   ///< extension: repulsion from the interpolated surface (no particle switching)
  smooth,    ///< extension: a C2 potential on the smooth spline surface (section 4.11)
};

/// Collision parameters of the paper's section 2.3 (docs/model.md section 4).
struct CollisionParams {
  double threshold = 0.01;    ///< delta: distance below which the repulsion acts [m]
  double stiffness = 1000.0;  ///< k_collision [N/m]
  CollisionModel model = CollisionModel::particle;
  double friction = 0.0;            ///< mu: Coulomb coefficient against the object (section 4.12)
  double friction_epsilon = 1e-3;   ///< epsilon_v: the friction mollifier's width [m/s]
};

/// The collision term of one cloth particle against the object: force, energy, Jacobian and
/// penetration correction, for either model. The object feels nothing.
///
/// `particle` (the paper): with o the nearest object particle and d = |x - p_o| < delta,
/// force k (delta - d) (x - p_o) / d, energy k (delta - d)^2 / 2; a particle inside the surface
/// moves onto p_o. `surface`: with the radial gap g = r_h - R(y, theta) to the interpolated
/// surface (Dummy::surface_gap) and g < delta, energy k (delta - g)^2 / 2 and force
/// k (delta - g) grad g; a particle inside moves radially onto the surface. `smooth`: with the
/// C2 gap G of SmoothSurface, energy k/(3 delta) (delta - G)^3 for 0 <= G < delta, continued
/// quadratically inside (smooth_contact.hpp), its exact Hessian (projected to positive
/// semi-definite for the definite Jacobian), and a particle inside moves onto G = 0 along
/// grad G. All remove the inward normal velocity of a corrected
/// particle.
///
/// Contact pairing (the implicit integrators' contact set of a step, docs/integrators/arkode.md):
/// after pair_contacts(x), until the next pair_contacts() or unpair_contacts(), each cloth
/// particle i keeps the contact it had at x_i, linearised there: with g the contact's gap (the
/// distance |x - p_o| to the object particle o nearest to x_i, or the surface gap) and n its
/// gradient at x_i, the gap is the tangent plane's g(x_i) + n . (x - x_i), the force
/// k (delta - g) n, the Jacobian -k n n^T, for a particle with g(x_i) < 2 delta. The force no
/// longer jumps where the nearest object particle switches, where the surface's gradient jumps
/// (section heights, angle bins) or through an object particle (the point repulsion turns its
/// direction around there, and a corrected penetration puts a particle exactly on it), so
/// Newton's method on an implicit stage sees a piecewise linear force (a kink at the threshold).
/// At the positions x themselves it equals the unpaired force bit for bit. The `smooth` model
/// needs no pairing: pair_contacts() leaves it unpaired.
class Collision {
 public:
  /// `dummy` may be null: then every term is zero.
  Collision(std::shared_ptr<const Dummy> dummy, const CollisionParams& params, int num_particles);

  const CollisionParams& params() const { return m_params; }
  /// Force on cloth particle i at x.
  Vec3 force(int i, const Vec3& x) const;
  /// Collision energy of cloth particle i at x.
  double energy(int i, const Vec3& x) const;
  /// dF/dx of cloth particle i at x. The surface model uses the Gauss-Newton part
  /// -k grad g grad g^T (it drops the surface's curvature term), definite either way. The
  /// smooth model gives minus its energy's exact Hessian, projected to PSD when definite.
  Mat3 jacobian(int i, const Vec3& x, bool definite) const;
  /// Moves cloth particle i, found inside the object, out of it and removes its inward normal
  /// velocity; returns whether it was inside.
  bool correct_penetration(int i, Vec3& x, Vec3& v) const;

  /// Fixes and linearises every cloth particle's contact at its position in x (3N).
  void pair_contacts(ConstVecRef x);
  /// Back to the contact at every evaluation (the model of docs/model.md section 4).
  void unpair_contacts() { m_planes.clear(); }
  /// `particle` model: the object particle paired with cloth particle i (-1: none, unpaired, or
  /// the surface model).
  int paired(int i) const {
    return m_planes.empty() ? -1 : m_planes[static_cast<std::size_t>(i)].object;
  }

 private:
  /// A contact linearised at pair_contacts(): the gap at `anchor` and its gradient. The force
  /// is k (delta - gap) push / push_length, push / push_length = gradient, written as the
  /// unpaired force is computed so that the two agree bit for bit at the anchor.
  struct ContactPlane {
    Vec3 anchor = Vec3::Zero();
    double gap = 0.0;
    Vec3 gradient = Vec3::Zero();
    Vec3 push = Vec3::Zero();
    double push_length = 1.0;
    int object = -1;      ///< `particle`: the object particle
    bool active = false;  ///< false: no contact over this step
  };

  /// The plane's gap at x, or nothing without a contact.
  std::optional<double> plane_gap(int i, const Vec3& x) const;
  Vec3 paired_force(int i, const Vec3& x) const;
  ContactPlane particle_plane(const Vec3& x) const;
  ContactPlane surface_plane(const Vec3& x) const;
  Vec3 surface_force(const Vec3& x) const;
  bool correct_penetration_off_margin(int i, Vec3& x, Vec3& v) const;
  Vec3 smooth_force(const Vec3& x) const;
  bool correct_smooth_penetration(Vec3& x, Vec3& v) const;

  std::shared_ptr<const Dummy> m_dummy;
  CollisionParams m_params;
  ContactFinder m_contacts;
  std::optional<SmoothSurface> m_smooth;  // the `smooth` model's surface, built once
  // Per cloth particle, a point and a distance within which nothing is inside the object
  // (Dummy::outside_margin): a fact about space, true whatever the particle does, so a particle
  // still within it needs no penetration test. Mutable like ContactFinder's lists.
  mutable Eigen::VectorXd m_outside_anchor;   // 3N
  mutable Eigen::VectorXd m_outside_margin2;  // N, squared; -1 before the first test
  std::vector<ContactPlane> m_planes;  // N while paired, empty otherwise
};

// The force evaluation's hot path, inline: it runs for every cloth particle at every evaluation.

inline bool Collision::correct_penetration(int i, Vec3& x, Vec3& v) const {
  if (!m_dummy) return false;
  if (m_smooth) return correct_smooth_penetration(x, v);
  // Both models' inside is the radial gap below 0 between the end sections: nothing within the
  // margin of the anchor is.
  if ((x - m_outside_anchor.segment<3>(3 * i)).squaredNorm() < m_outside_margin2[i]) return false;
  return correct_penetration_off_margin(i, x, v);
}

inline std::optional<double> Collision::plane_gap(int i, const Vec3& x) const {
  const ContactPlane& c = m_planes[static_cast<std::size_t>(i)];
  if (!c.active) return std::nullopt;
  // Written from the anchor, so that at the anchor itself the gap is the contact's exactly.
  return c.gap + c.gradient.dot(x - c.anchor);
}

inline Vec3 Collision::paired_force(int i, const Vec3& x) const {
  const std::optional<double> g = plane_gap(i, x);
  const double delta = m_params.threshold;
  if (!g || *g >= delta) return Vec3::Zero();
  const ContactPlane& c = m_planes[static_cast<std::size_t>(i)];
  return (m_params.stiffness * (delta - *g) / c.push_length) * c.push;
}

inline Vec3 Collision::force(int i, const Vec3& x) const {
  if (!m_dummy) return Vec3::Zero();
  if (!m_planes.empty()) return paired_force(i, x);
  if (m_params.model == CollisionModel::surface) return surface_force(x);
  if (m_smooth) return smooth_force(x);
  const NearestObjectParticle hit = m_contacts.nearest(i, x);
  if (hit.index < 0) return Vec3::Zero();
  return collision_force(x - m_dummy->position(hit.index), hit.distance,
                         m_dummy->normal(hit.index), m_params.stiffness, m_params.threshold);
}

}  // namespace drape
