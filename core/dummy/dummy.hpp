#pragma once
// The object (dummy) model of the paper, section 2.1: particles on horizontal cross-sections,
// no springs. Section k (k = 0 at the top) has height y_k, centre (cx_k, cz_k) and one radius
// per angle theta_j = 2*pi*j/points, measured from the front (+z) towards +x. Object particle
// o = k*points + j sits at (cx_k + rho sin theta_j, y_k, cz_k + rho cos theta_j).
#include <memory>
#include <optional>
#include <vector>

#include "core/dummy/nearest_particle_grid.hpp"
#include "core/state/state.hpp"

namespace drape {

/// Heights, centres and radii of a stack of cross-sections: the data every dummy source yields.
struct DummySections {
  std::vector<double> y;   ///< height of each section, strictly decreasing (top first)
  std::vector<double> cx;  ///< section centre x
  std::vector<double> cz;  ///< section centre z
  Eigen::MatrixXd radius;  ///< sections x points: radius at theta_j = 2*pi*j/points

  int num_sections() const { return static_cast<int>(y.size()); }
  int points() const { return static_cast<int>(radius.cols()); }
};

/// An object particle nearest to a query point, with its Euclidean distance.
struct NearestObjectParticle {
  int index = -1;  ///< object particle index, -1 when none qualifies
  double distance = 0.0;
};

/// Where a point is relative to the interpolated surface (the `surface` collision model):
/// the radial gap g = r_h - R(y, theta), r_h the horizontal distance from the interpolated axis,
/// and its gradient with respect to the point.
struct SurfaceGap {
  double gap = 0.0;
  Vec3 gradient = Vec3::Zero();
};

/// The particle dummy: positions, outward normals, nearest-particle queries, inside test.
class Dummy {
 public:
  explicit Dummy(DummySections sections);

  int num_sections() const { return m_sections.num_sections(); }
  int points() const { return m_sections.points(); }
  /// Number of object particles (sections * points).
  int size() const { return num_sections() * points(); }
  const DummySections& sections() const { return m_sections; }

  /// All object particle positions, interleaved xyz (3 * size()).
  const Eigen::VectorXd& positions() const { return m_positions; }
  Vec3 position(int o) const { return m_positions.segment<3>(3 * o); }
  /// Outward unit normal of object particle o: (sin theta_j, 0, cos theta_j).
  Vec3 normal(int o) const { return m_normals.segment<3>(3 * o); }
  /// Angle theta_j of column j.
  double angle(int j) const;

  /// Exact nearest object particle to p (Euclidean), never a scan of all particles.
  NearestObjectParticle nearest(const Vec3& p) const;
  /// Nearest object particle with distance < radius, or index -1. The collision hot path.
  NearestObjectParticle nearest_within(const Vec3& p, double radius) const;
  /// Indices of every object particle at distance < radius from p, ascending.
  void particles_within(const Vec3& p, double radius, std::vector<int>& out) const;
  /// Test oracle: nearest by scanning every object particle.
  NearestObjectParticle nearest_brute_force(const Vec3& p) const;

  /// Surface radius at height y and angle theta: linear in height between the bracketing
  /// sections and linear in angle between the bracketing particles of each section.
  double surface_radius(double y, double theta) const;
  /// Section centre (cx, cz) interpolated linearly in height.
  Eigen::Vector2d axis_at(double y) const;
  /// The radial gap to the interpolated surface and its gradient, for p between the top and
  /// bottom sections and off the axis; nothing elsewhere (the stack is open at its ends).
  std::optional<SurfaceGap> surface_gap(const Vec3& p) const;
  /// True when p lies between the top and bottom sections and its horizontal distance from the
  /// interpolated axis is below the surface radius at its angle (docs/model.md section 4, penetration).
  bool inside(const Vec3& p) const;
  /// A distance within which no point is inside(): every q with |q - p| < outside_margin(p) has
  /// inside(q) false. 0 when p is inside or too near the surface to say (a lower bound, from a
  /// Lipschitz constant of the gap; see lipschitz_constant()).
  double outside_margin(const Vec3& p) const;
  /// L with |phi(p) - phi(q)| <= L |p - q| for the radial gap phi = r_h - R(y, theta) (y clamped
  /// to the stack) wherever phi >= 0; infinite when a radius is 0.
  double lipschitz_constant() const { return m_lipschitz; }

 private:
  /// Section k with y_k >= y >= y_{k+1} (y clamped to the stack) and the weight t of k + 1.
  int bracket(double y, double& t) const;
  /// The particles j, j1 on either side of angle theta and the weight f of j1.
  struct AngleBin {
    int j, j1;
    double f;
  };
  AngleBin angle_bin(double theta) const;
  /// Radius of section k at angle theta, linear between its two neighbouring particles.
  double section_radius(int k, double theta) const;
  /// d/dtheta of section_radius (constant along each edge between two particles).
  double section_radius_slope(int k, double theta) const;
  /// Section centre and surface radius at weight t between sections k and k + 1.
  Eigen::Vector2d axis_between(int k, double t) const;
  double radius_between(int k, double t, double theta) const;

  DummySections m_sections;
  Eigen::VectorXd m_positions;
  Eigen::VectorXd m_normals;
  detail::ParticleGrid m_grid;        // nearest-particle queries
  Eigen::VectorXd m_min_radius;       // per section: cheap bounds that decide most inside() calls
  Eigen::VectorXd m_max_radius;
  double m_sections_per_metre = 0.0;  // first guess of the bracketing section from a height
  double m_lipschitz = 0.0;           // of the radial gap, for outside_margin()
};

}  // namespace drape
