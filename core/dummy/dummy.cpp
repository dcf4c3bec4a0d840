#include "core/dummy/dummy.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace drape {

namespace {

constexpr double kTwoPi = 6.283185307179586476925286766559;

// The gap phi = r_h - R(y, theta) of a point whose horizontal distance from the axis is r_h, over
// the whole stack (y clamped, so phi does not change with y above or below it). Its gradient:
//   horizontal part: radial - (dR/dtheta / r_h) tangent, norm <= 1 + S / r_h;
//   d/dy: -radial . c'(y) - dR/dy - dR/dtheta (tangent . c'(y)) / r_h, |.| <= A + D + S A / r_h;
// with S = max |dR/dtheta| (the steepest edge between neighbouring particles of a section),
// D = max |dR/dy| (the largest change of one column's radius over a section gap, per metre) and
// A = max |c'(y)| (the steepest lean of the axis between two sections). Where phi >= 0,
// r_h >= R >= R_min, the smallest radius, so there |grad phi| <= L = 1 + A + D + S (1 + A) / R_min.
// A straight path from a point with phi > 0 to one inside crosses phi = 0 first, and phi >= 0 on
// the way, so it is at least phi / L long (phi is continuous and piecewise smooth: its kinks at
// sections and particle angles do not matter).
double gap_lipschitz_constant(const DummySections& s) {
  const int n = s.num_sections(), m = s.points();
  const double r_min = s.radius.minCoeff();
  if (!(r_min > 0.0)) return std::numeric_limits<double>::infinity();
  double axis = 0.0, height = 0.0, angle = 0.0;
  for (int k = 0; k + 1 < n; ++k) {
    const double dy = s.y[k] - s.y[k + 1];
    axis = std::max(axis, std::hypot(s.cx[k] - s.cx[k + 1], s.cz[k] - s.cz[k + 1]) / dy);
    height = std::max(height, (s.radius.row(k) - s.radius.row(k + 1)).cwiseAbs().maxCoeff() / dy);
  }
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < m; ++j)
      angle = std::max(angle, std::abs(s.radius(k, (j + 1) % m) - s.radius(k, j)) * m / kTwoPi);
  return 1.0 + axis + height + angle * (1.0 + axis) / r_min;
}

void check_sections(const DummySections& s) {
  const int n = s.num_sections();
  if (n < 2) throw std::invalid_argument("a dummy needs at least 2 sections");
  if (s.points() < 3) throw std::invalid_argument("a dummy needs at least 3 points per section");
  if (static_cast<int>(s.cx.size()) != n || static_cast<int>(s.cz.size()) != n ||
      s.radius.rows() != n)
    throw std::invalid_argument("dummy sections: y, cx, cz and radius rows differ in length");
  for (int k = 0; k < n; ++k) {
    if (!std::isfinite(s.y[k]) || !std::isfinite(s.cx[k]) || !std::isfinite(s.cz[k]))
      throw std::invalid_argument("dummy section " + std::to_string(k) + " is not finite");
    if (k > 0 && !(s.y[k] < s.y[k - 1]))
      throw std::invalid_argument("dummy section heights must strictly decrease (top first)");
  }
  if (!s.radius.allFinite() || (s.radius.array() < 0.0).any())
    throw std::invalid_argument("dummy radii must be finite and non-negative");
}

}  // namespace

Dummy::Dummy(DummySections sections) : m_sections(std::move(sections)) {
  check_sections(m_sections);
  const int n = num_sections();
  const int m = points();
  m_positions.resize(3 * size());
  m_normals.resize(3 * size());
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < m; ++j) {
      const double s = std::sin(angle(j));
      const double c = std::cos(angle(j));
      const double r = m_sections.radius(k, j);
      const int o = k * m + j;
      m_positions.segment<3>(3 * o) = Vec3(m_sections.cx[k] + r * s, m_sections.y[k],
                                           m_sections.cz[k] + r * c);
      m_normals.segment<3>(3 * o) = Vec3(s, 0.0, c);
    }
  m_min_radius = m_sections.radius.rowwise().minCoeff();
  m_max_radius = m_sections.radius.rowwise().maxCoeff();
  const double height = m_sections.y.front() - m_sections.y.back();
  m_sections_per_metre = (n - 1) / height;
  m_lipschitz = gap_lipschitz_constant(m_sections);

  // Cell size from the particle spacing, so that the work per query does not grow with the
  // resolution: twice the geometric mean of the section spacing and the mean arc between
  // neighbours puts a few particles in each cell the surface crosses, and a query of the
  // collision threshold's size reads at most 2 x 2 rows of cells. (Measured on the dress form:
  // from 1 to 5 mean spacings the cost changes by under 20 %; 2 is at the flat minimum.)
  const double section_spacing = height / (n - 1);
  const double arc_spacing = kTwoPi * m_sections.radius.mean() / m;
  const double cell = 2.0 * (arc_spacing > 0.0 ? std::sqrt(section_spacing * arc_spacing)
                                               : section_spacing);
  m_grid = detail::ParticleGrid(m_positions, cell);
}

void Dummy::particles_within(const Vec3& p, double radius, std::vector<int>& out) const {
  out.clear();
  if (!p.allFinite()) return;  // no contact for a non-finite point
  m_grid.for_each_within(p, radius, [&](int o) { out.push_back(o); });
  std::sort(out.begin(), out.end());
}

double Dummy::angle(int j) const { return kTwoPi * j / points(); }

NearestObjectParticle Dummy::nearest(const Vec3& p) const {
  if (!p.allFinite()) return {};  // index -1: a non-finite point has no nearest particle
  const detail::GridHit hit = m_grid.nearest(p);
  return {hit.index, std::sqrt(hit.distance_squared)};
}

NearestObjectParticle Dummy::nearest_within(const Vec3& p, double radius) const {
  // A non-finite point (a run about to end diverged) is in contact with nothing.
  if (!p.allFinite()) return {};
  const detail::GridHit hit = m_grid.nearest_within(p, radius);
  if (hit.index < 0) return {};
  return {hit.index, std::sqrt(hit.distance_squared)};
}

NearestObjectParticle Dummy::nearest_brute_force(const Vec3& p) const {
  detail::GridHit best{-1, 0.0};
  for (int o = 0; o < size(); ++o) {
    const double d2 = detail::distance_squared(m_positions.data() + 3 * o, p);
    if (best.index < 0 || d2 < best.distance_squared) best = {o, d2};
  }
  return {best.index, std::sqrt(best.distance_squared)};
}

int Dummy::bracket(double y, double& t) const {
  const auto& ys = m_sections.y;
  const int last = num_sections() - 2;
  if (!std::isfinite(y)) {  // a NaN must not become a section index; callers reject it first
    t = 0.0;
    return 0;
  }
  if (y >= ys.front()) {
    t = 0.0;
    return 0;
  }
  if (y <= ys.back()) {
    t = 1.0;
    return last;
  }
  // Evenly spaced sections (every built-in source after resampling) are hit by the first guess;
  // the walk corrects it for any other strictly decreasing stack.
  int k = static_cast<int>((ys.front() - y) * m_sections_per_metre);
  k = k < 0 ? 0 : (k > last ? last : k);
  while (k > 0 && y > ys[k]) --k;
  while (k < last && y < ys[k + 1]) ++k;
  t = (ys[k] - y) / (ys[k] - ys[k + 1]);
  return k;
}

Dummy::AngleBin Dummy::angle_bin(double theta) const {
  const int m = points();
  double u = theta * (m / kTwoPi);
  u -= m * std::floor(u / m);  // wrap into [0, m)
  if (!(u >= 0.0)) u = 0.0;    // a NaN angle (from a non-finite point) must not become an index
  int j = static_cast<int>(u);
  if (j >= m) j = m - 1;  // u rounded up to m
  return {j, j + 1 == m ? 0 : j + 1, u - j};
}

double Dummy::section_radius(int k, double theta) const {
  const AngleBin b = angle_bin(theta);
  return (1.0 - b.f) * m_sections.radius(k, b.j) + b.f * m_sections.radius(k, b.j1);
}

double Dummy::section_radius_slope(int k, double theta) const {
  const AngleBin b = angle_bin(theta);
  return (m_sections.radius(k, b.j1) - m_sections.radius(k, b.j)) * (points() / kTwoPi);
}

Eigen::Vector2d Dummy::axis_between(int k, double t) const {
  return {(1.0 - t) * m_sections.cx[k] + t * m_sections.cx[k + 1],
          (1.0 - t) * m_sections.cz[k] + t * m_sections.cz[k + 1]};
}

double Dummy::radius_between(int k, double t, double theta) const {
  return (1.0 - t) * section_radius(k, theta) + t * section_radius(k + 1, theta);
}

std::optional<SurfaceGap> Dummy::surface_gap(const Vec3& p) const {
  if (!p.allFinite()) return std::nullopt;  // no contact for a non-finite point
  const auto& ys = m_sections.y;
  if (!(p.y() < ys.front() && p.y() > ys.back())) return std::nullopt;
  double t = 0.0;
  const int k = bracket(p.y(), t);
  const double dy = ys[k] - ys[k + 1];
  const Eigen::Vector2d axis = axis_between(k, t);
  // d(axis)/dy: t grows downwards, so dt/dy = -1/dy.
  const Eigen::Vector2d axis_slope((m_sections.cx[k] - m_sections.cx[k + 1]) / dy,
                                   (m_sections.cz[k] - m_sections.cz[k + 1]) / dy);
  const double hx = p.x() - axis.x(), hz = p.z() - axis.y();
  const double r = std::hypot(hx, hz);
  if (r < 1e-12) return std::nullopt;  // on the axis the angle, and so the gap, is undefined
  const double theta = std::atan2(hx, hz);
  const Vec3 radial(hx / r, 0.0, hz / r);       // direction of increasing r_h
  const Vec3 tangent(hz / r, 0.0, -hx / r);     // direction of increasing theta
  const double r_k = section_radius(k, theta), r_k1 = section_radius(k + 1, theta);
  const double dR_dtheta =
      (1.0 - t) * section_radius_slope(k, theta) + t * section_radius_slope(k + 1, theta);
  const double dR_dy = (r_k - r_k1) / dy;
  // g = r_h - R(y, theta(x, y)) with r_h and theta measured from the axis (cx(y), cz(y)):
  // moving up by dy moves the axis by axis_slope dy, which changes both r_h and theta.
  const double axis_radial = radial.x() * axis_slope.x() + radial.z() * axis_slope.y();
  const double axis_tangent = tangent.x() * axis_slope.x() + tangent.z() * axis_slope.y();
  SurfaceGap g;
  g.gap = r - ((1.0 - t) * r_k + t * r_k1);
  g.gradient = radial - (dR_dtheta / r) * tangent;
  g.gradient.y() = -axis_radial - dR_dy + dR_dtheta * axis_tangent / r;
  return g;
}

double Dummy::surface_radius(double y, double theta) const {
  double t = 0.0;
  const int k = bracket(y, t);
  return radius_between(k, t, theta);
}

Eigen::Vector2d Dummy::axis_at(double y) const {
  double t = 0.0;
  const int k = bracket(y, t);
  return axis_between(k, t);
}

bool Dummy::inside(const Vec3& p) const {
  if (!p.allFinite()) return false;  // no contact for a non-finite point
  if (!(p.y() <= m_sections.y.front() && p.y() >= m_sections.y.back())) return false;
  double t = 0.0;
  const int k = bracket(p.y(), t);
  const Eigen::Vector2d axis = axis_between(k, t);
  const double dx = p.x() - axis.x();
  const double dz = p.z() - axis.y();
  const double d2 = dx * dx + dz * dz;
  // The surface radius at any angle lies between the interpolated per-section extremes, which
  // settles most points without an atan2.
  const double low = (1.0 - t) * m_min_radius[k] + t * m_min_radius[k + 1];
  if (d2 < low * low) return true;
  const double high = (1.0 - t) * m_max_radius[k] + t * m_max_radius[k + 1];
  if (d2 >= high * high) return false;
  const double theta = std::atan2(dx, dz);
  const double r = radius_between(k, t, theta);
  return d2 < r * r;
}

double Dummy::outside_margin(const Vec3& p) const {
  if (!p.allFinite()) return 0.0;  // nothing can be said of a non-finite point
  const auto& ys = m_sections.y;
  // Above the top or below the bottom section nothing is inside until y reaches the stack.
  const double out_of_range = std::max(p.y() - ys.front(), ys.back() - p.y());
  double t = 0.0;
  const int k = bracket(p.y(), t);
  const Eigen::Vector2d axis = axis_between(k, t);
  const double dx = p.x() - axis.x();
  const double dz = p.z() - axis.y();
  const double theta = std::atan2(dx, dz);
  const double gap = std::sqrt(dx * dx + dz * dz) - radius_between(k, t, theta);
  const double margin = std::max(out_of_range, gap / m_lipschitz);
  // The guard, far above the round-off of inside() and of this function for points within
  // metres of the origin, keeps a point whose margin we trust away from the surface.
  constexpr double guard = 1e-9;
  return margin > guard ? margin - guard : 0.0;
}

}  // namespace drape
