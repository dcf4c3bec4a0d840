// The smooth gap: value, gradient and Hessian against finite differences on every dummy source,
// continuity across section heights, angle bins, caps and the axis, and closed forms on the
// cylinder and the sphere.
#include "core/dummy/smooth_surface.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include "core/dummy/dummy_sources.hpp"

namespace drape {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

DummySections sections_of(const json& spec) {
  return make_dummy_sections(spec, "scene.json", "dummy", DRAPE_SOURCE_DIR);
}

// Central differences: the gradient against the value, the Hessian against the gradient.
// Their truncation error is O(h^2) times third (fourth) derivatives; round-off O(eps/h).
void expect_derivatives_match(const SmoothSurface& s, const Vec3& p, const std::string& where) {
  const SmoothGap g = s.gap(p);
  const double h = 1e-6;
  Vec3 fd_gradient;
  Mat3 fd_hessian;
  for (int a = 0; a < 3; ++a) {
    const Vec3 e = h * Vec3::Unit(a);
    const SmoothGap plus = s.gap(p + e), minus = s.gap(p - e);
    fd_gradient[a] = (plus.gap - minus.gap) / (2.0 * h);
    fd_hessian.col(a) = (plus.gradient - minus.gradient) / (2.0 * h);
  }
  EXPECT_LT((fd_gradient - g.gradient).norm(), 1e-6 * (1.0 + g.gradient.norm())) << where;
  EXPECT_LT((fd_hessian - g.hessian).norm(), 2e-4 * (1.0 + g.hessian.norm()))
      << where << "\n" << g.hessian << "\nfd\n" << fd_hessian;
  EXPECT_LT((g.hessian - g.hessian.transpose()).norm(), 1e-9 * (1.0 + g.hessian.norm())) << where;
}

// Points within 3 cm of the surface over the whole stack and beyond its ends, some near the axis.
std::vector<Vec3> around(const DummySections& d, const SmoothSurface& s, int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double top = d.y.front(), bottom = d.y.back(), reach = 4.0 * s.blend_width();
  std::vector<Vec3> points;
  for (int i = 0; i < count; ++i) {
    const double y = bottom - reach + (top - bottom + 2.0 * reach) * u(rng);
    const double theta = 2.0 * M_PI * u(rng);
    const Eigen::Vector2d c = s.axis(y);
    // Every fourth point near the axis, the rest near the surface.
    const double r = i % 4 == 0 ? 1.2 * s.axis_radius() * u(rng)
                                : std::max(0.0, s.radius(y, theta)) + 0.06 * (u(rng) - 0.5);
    points.emplace_back(c.x() + r * std::sin(theta), y, c.y() + r * std::cos(theta));
  }
  return points;
}

void expect_smooth_everywhere(const DummySections& d, const std::string& name) {
  const SmoothSurface s(d);
  int i = 0;
  for (const Vec3& p : around(d, s, 400, 7))
    expect_derivatives_match(s, p, name + " point " + std::to_string(i++));
}

TEST(SmoothSurface, DerivativesMatchFiniteDifferencesOnEverySource) {
  expect_smooth_everywhere(sections_of({{"builtin", "dress-form"}}), "dress form");
  expect_smooth_everywhere(sections_of({{"builtin", "cylinder"}, {"radius", 0.1}, {"center", {0.02, -0.01}},
                                        {"y_top", 1.0}, {"y_bottom", 0.5}, {"sections", 12}}),
                           "cylinder");
  expect_smooth_everywhere(sections_of({{"builtin", "sphere"}, {"radius", 0.3}, {"center", {0.0, 0.6, 0.1}}}),
                           "sphere");
  const fs::path file = fs::path(::testing::TempDir()) / "smooth_sections.json";
  std::ofstream(file) << R"({"sections": [
    {"y": 1.40, "center": [0.00, 0.02], "radii": [0.05, 0.06, 0.08, 0.06, 0.07]},
    {"y": 1.30, "center": [0.01, 0.03], "radii": [0.12, 0.15, 0.11, 0.15, 0.10]},
    {"y": 1.15, "center": [0.00, 0.01], "radii": [0.10, 0.12, 0.13, 0.11, 0.12]}]})";
  expect_smooth_everywhere(sections_of({{"file", file.string()}, {"sections", 5}, {"points", 5}}),
                           "sections file");
  expect_smooth_everywhere(
      sections_of({{"mesh", "core/dummy/data/dress-form/mh_default_female_body_cm.obj"}, {"unit", 0.01},
                   {"y_top", 1.195}, {"y_bottom", 0.755}, {"sections", 16}, {"points", 24}}),
      "mesh");
}

// Differences of value, gradient and Hessian between two points 2 eps apart.
double jump(const SmoothSurface& s, const Vec3& a, const Vec3& b) {
  const SmoothGap ga = s.gap(a), gb = s.gap(b);
  return std::abs(ga.gap - gb.gap) + (ga.gradient - gb.gradient).norm() +
         (ga.hessian - gb.hessian).norm() / (1.0 + ga.hessian.norm());
}

TEST(SmoothSurface, GradientAndHessianAreContinuousAcrossSectionsAnglesAndCaps) {
  const DummySections d = sections_of({{"builtin", "dress-form"}});
  const SmoothSurface s(d);
  const int m = d.points();
  for (const double eps : {1e-5, 1e-7}) {
    double worst = 0.0;
    // Across every section height, and the ends (y_top, y_bottom) and blend edges of the caps.
    std::vector<double> heights(d.y);
    for (const double y : {d.y.front(), d.y.back()})
      for (const double off : {-1.0, 1.0}) heights.push_back(y + off * s.blend_width());
    for (std::size_t k = 0; k < heights.size(); ++k) {
      const double theta = 0.37 + 0.5 * static_cast<double>(k);
      const Eigen::Vector2d c = s.axis(heights[k]);
      const double r = s.radius(heights[k], theta) + 0.003;
      const Vec3 p(c.x() + r * std::sin(theta), heights[k], c.y() + r * std::cos(theta));
      worst = std::max(worst, jump(s, p + eps * Vec3::UnitY(), p - eps * Vec3::UnitY()));
    }
    // Across every angle bin boundary, at a height between sections.
    for (int j = 0; j < m; ++j) {
      const double y = 1.1, theta = 2.0 * M_PI * j / m;
      const Eigen::Vector2d c = s.axis(y);
      const auto at = [&](double t) {
        const double r = s.radius(y, theta) + 0.002;
        return Vec3(c.x() + r * std::sin(t), y, c.y() + r * std::cos(t));
      };
      worst = std::max(worst, jump(s, at(theta + eps), at(theta - eps)));
    }
    // Across the axis treatment's two radii.
    for (const double r : {0.5 * s.axis_radius(), s.axis_radius()}) {
      const Eigen::Vector2d c = s.axis(1.0);
      worst = std::max(worst, jump(s, Vec3(c.x() + r + eps, 1.0, c.y()), Vec3(c.x() + r - eps, 1.0, c.y())));
    }
    // Lipschitz Hessian: jumps shrink in proportion to eps (the linear surface's gradient jumps
    // by O(1) at the same places).
    EXPECT_LT(worst, 2e4 * eps) << "eps " << eps;
  }
}

TEST(SmoothSurface, CylinderRadiusIsExact) {
  const DummySections d = sections_of({{"builtin", "cylinder"}, {"radius", 0.12}, {"center", {0.05, -0.02}},
                                       {"y_top", 1.2}, {"y_bottom", 0.6}, {"sections", 9}, {"points", 7}});
  const SmoothSurface s(d);
  int checked = 0;
  for (int i = 0; i <= 100; ++i) {
    const double y = 0.5 + 0.008 * i, theta = 0.173 * i;
    EXPECT_NEAR(s.radius(y, theta), 0.12, 1e-14) << y;
    EXPECT_NEAR((s.axis(y) - Eigen::Vector2d(0.05, -0.02)).norm(), 0.0, 1e-14);
    // Where the side gap exceeds both end planes' by the blend width, it is r_h - R exactly.
    const double r = 0.1 + 0.0005 * i;
    if (r - 0.12 - (y - 1.2) >= s.blend_width() && r - 0.12 - (0.6 - y) >= s.blend_width()) {
      const Vec3 p(0.05 + r * std::sin(theta), y, -0.02 + r * std::cos(theta));
      EXPECT_NEAR(s.gap(p).gap, r - 0.12, 1e-14);
      ++checked;
    }
  }
  EXPECT_GT(checked, 20);
}

// The natural spline through f(y) = sqrt(R^2 - y^2) at the sphere's section heights: away from
// the poles, the error of a cubic spline interpolant is at most 5/384 h^4 max|f''''| (Hall 1968)
// plus the end condition's error, which decays by a factor 2 - sqrt(3) per knot: negligible
// 20 knots in. f'''' = -3 R^2 (R^2 + 4 y^2) / (R^2 - y^2)^(7/2).
TEST(SmoothSurface, SphereRadiusWithinTheInterpolationBound) {
  const double R = 0.3, yc = 0.6;
  const int n = 80;
  const SmoothSurface s(sections_of({{"builtin", "sphere"}, {"radius", R}, {"center", {0.0, yc, 0.0}},
                                     {"sections", n}}));
  const double band = 0.7 * R;
  const double spacing = M_PI * R / n;  // every gap between section heights is below the arc
  const double f4 = 3.0 * R * R * (R * R + 4 * band * band) / std::pow(R * R - band * band, 3.5);
  const double bound = 5.0 / 384.0 * std::pow(spacing, 4) * f4;
  double worst = 0.0;
  for (int i = 0; i <= 200; ++i) {
    const double dy = -band + 2.0 * band * i / 200.0;
    worst = std::max(worst, std::abs(s.radius(yc + dy, 0.1 * i) - std::sqrt(R * R - dy * dy)));
  }
  EXPECT_LT(worst, bound) << "bound " << bound;
  EXPECT_LT(worst, 1e-6);
}

}  // namespace
}  // namespace drape

namespace drape {
namespace {

// The sphere's poles are domes (sections flatter than SmoothSurface::kDomeSlope): closed by
// paraboloid caps, the gap is about the distance all over the sphere. Measured on 200000 points
// (docs/model.md section 4.11): |G - d| <= 1.6 mm and 0.61 <= |grad G| <= 1.14 within the
// contact band, G >= 0.52 d beyond 2 cm. Before the caps the slope-scaled radial gap near the
// top was below 1 cm up to 15 cm out (an invisible shelf) and |grad G| reached 6.5.
TEST(SmoothSurface, SphereGapIsAboutTheDistanceUpToThePoles) {
  const double R = 0.15, delta = 0.01;
  const Vec3 centre(0.0, 0.5, 0.0);
  const SmoothSurface s(sections_of({{"builtin", "sphere"}, {"radius", R}, {"center", {0.0, 0.5, 0.0}}}));
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 20000; ++i) {
    const double c = 2.0 * u(rng) - 1.0, phi = 2.0 * M_PI * u(rng), sn = std::sqrt(1.0 - c * c);
    const double d = -0.005 + 0.06 * u(rng);
    const Vec3 p = centre + (R + d) * Vec3(sn * std::cos(phi), c, sn * std::sin(phi));
    const SmoothGap g = s.gap(p);
    if (d <= delta) {
      EXPECT_NEAR(g.gap, d, 0.002) << p.transpose();
      EXPECT_GT(g.gradient.norm(), 0.6) << p.transpose();
      EXPECT_LT(g.gradient.norm(), 1.2) << p.transpose();
    } else if (d >= 2.0 * delta) {
      EXPECT_GE(g.gap, 0.5 * d) << p.transpose();
    }
  }
}

}  // namespace
}  // namespace drape
