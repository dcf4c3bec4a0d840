#include "core/dummy/dummy.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

#include "core/dummy/dress_form.hpp"
#include "core/dummy/dummy_sources.hpp"

namespace drape {
namespace {

constexpr double kPi = 3.141592653589793238462643383279;

// Uneven sections: varying heights, centres and radii, so that no formula holds by symmetry.
DummySections irregular_sections(int sections, int points, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  DummySections s;
  double y = 1.5;
  for (int k = 0; k < sections; ++k) {
    y -= 0.005 + 0.02 * u(rng);
    s.y.push_back(y);
    s.cx.push_back(0.05 * (u(rng) - 0.5));
    s.cz.push_back(0.05 * (u(rng) - 0.5));
  }
  s.radius.resize(sections, points);
  for (int k = 0; k < sections; ++k)
    for (int j = 0; j < points; ++j) s.radius(k, j) = 0.1 + 0.1 * u(rng);
  return s;
}

TEST(Dummy, PositionsAndNormalsFollowTheSpecFormula) {
  const DummySections s = irregular_sections(7, 11, 1);
  const Dummy dummy(s);
  ASSERT_EQ(dummy.size(), 77);
  ASSERT_EQ(dummy.positions().size(), 3 * 77);
  for (int k = 0; k < 7; ++k)
    for (int j = 0; j < 11; ++j) {
      const int o = k * 11 + j;
      const double theta = 2.0 * kPi * j / 11;
      EXPECT_NEAR(dummy.angle(j), theta, 1e-15);
      const double r = s.radius(k, j);
      const Vec3 expected(s.cx[k] + r * std::sin(theta), s.y[k], s.cz[k] + r * std::cos(theta));
      EXPECT_LT((dummy.position(o) - expected).norm(), 1e-15);
      const Vec3 n = dummy.normal(o);
      EXPECT_NEAR(n.norm(), 1.0, 1e-15);
      EXPECT_EQ(n.y(), 0.0);
      EXPECT_LT((n - Vec3(std::sin(theta), 0.0, std::cos(theta))).norm(), 1e-15);
    }
  // Column 0 is the front centre line (+z), column points/4 looks towards +x.
  const Dummy cyl(cylinder_sections(0.2, 0.0, 0.0, 1.0, 0.0, 3, 8));
  EXPECT_LT((cyl.position(0) - Vec3(0.0, 1.0, 0.2)).norm(), 1e-15);
  EXPECT_LT((cyl.position(2) - Vec3(0.2, 1.0, 0.0)).norm(), 1e-15);
}

TEST(Dummy, RejectsInconsistentSections) {
  DummySections s = irregular_sections(4, 5, 2);
  std::swap(s.y[1], s.y[2]);
  EXPECT_THROW(Dummy{s}, std::invalid_argument);
  s = irregular_sections(4, 5, 2);
  s.cx.pop_back();
  EXPECT_THROW(Dummy{s}, std::invalid_argument);
  s = irregular_sections(4, 5, 2);
  s.radius(1, 1) = -0.1;
  EXPECT_THROW(Dummy{s}, std::invalid_argument);
  EXPECT_THROW(Dummy(irregular_sections(1, 5, 2)), std::invalid_argument);
  EXPECT_THROW(Dummy(irregular_sections(4, 2, 2)), std::invalid_argument);
}

TEST(Dummy, SurfaceRadiusIsBilinearInHeightAndAngle) {
  const DummySections s = irregular_sections(6, 9, 3);
  const Dummy dummy(s);
  const double step = 2.0 * kPi / 9;
  for (int k = 0; k < 6; ++k)
    for (int j = 0; j < 9; ++j) {
      const int j1 = (j + 1) % 9;
      EXPECT_NEAR(dummy.surface_radius(s.y[k], j * step), s.radius(k, j), 1e-14);
      // a quarter of the way to the next particle, also one turn earlier and later
      const double expected = 0.75 * s.radius(k, j) + 0.25 * s.radius(k, j1);
      for (double turn : {-2.0 * kPi, 0.0, 2.0 * kPi})
        EXPECT_NEAR(dummy.surface_radius(s.y[k], (j + 0.25) * step + turn), expected, 1e-13);
      if (k + 1 < 6) {
        const double y = 0.3 * s.y[k] + 0.7 * s.y[k + 1];
        EXPECT_NEAR(dummy.surface_radius(y, j * step),
                    0.3 * s.radius(k, j) + 0.7 * s.radius(k + 1, j), 1e-13);
        const Eigen::Vector2d axis = dummy.axis_at(y);
        EXPECT_NEAR(axis.x(), 0.3 * s.cx[k] + 0.7 * s.cx[k + 1], 1e-15);
        EXPECT_NEAR(axis.y(), 0.3 * s.cz[k] + 0.7 * s.cz[k + 1], 1e-15);
      }
    }
  // beyond the stack the end sections hold
  EXPECT_NEAR(dummy.surface_radius(s.y[0] + 1.0, 0.0), s.radius(0, 0), 1e-15);
  EXPECT_NEAR(dummy.surface_radius(s.y[5] - 1.0, 0.0), s.radius(5, 0), 1e-15);
}

TEST(Dummy, InsideCylinderClosedForm) {
  const double R = 0.15, cx = 0.1, cz = -0.2;
  const Dummy dummy(cylinder_sections(R, cx, cz, 1.2, 0.4, 40, 16));
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> angle(-kPi, kPi), height(0.4 + 1e-9, 1.2 - 1e-9);
  for (int i = 0; i < 2000; ++i) {
    const double a = angle(rng), y = height(rng);
    const auto at = [&](double r) {
      return Vec3(cx + r * std::sin(a), y, cz + r * std::cos(a));
    };
    EXPECT_NEAR(dummy.surface_radius(y, a), R, 1e-15);
    EXPECT_TRUE(dummy.inside(at(R * (1.0 - 1e-6))));
    EXPECT_FALSE(dummy.inside(at(R * (1.0 + 1e-6))));
    EXPECT_TRUE(dummy.inside(at(0.3 * R)));
  }
  EXPECT_TRUE(dummy.inside(Vec3(cx, 0.8, cz)));
  EXPECT_FALSE(dummy.inside(Vec3(cx, 1.2 + 1e-9, cz)));
  EXPECT_FALSE(dummy.inside(Vec3(cx, 0.4 - 1e-9, cz)));
}

TEST(Dummy, InsideSphereClosedForm) {
  const double R = 0.3;
  const Vec3 c(0.05, 1.0, -0.1);
  const int sections = 30;
  const Dummy dummy(sphere_sections(R, c, sections, 24));
  const auto& y = dummy.sections().y;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> angle(-kPi, kPi), u(0.0, 1.0);
  for (int i = 0; i < 2000; ++i) {
    // Between sections k and k + 1 the surface radius is the linear blend of R sin(phi).
    const int k = static_cast<int>(u(rng) * (sections - 1));
    const double t = u(rng);
    const double h = (1.0 - t) * y[k] + t * y[k + 1];
    const double expected = (1.0 - t) * R * std::sin(kPi * (k + 0.5) / sections) +
                            t * R * std::sin(kPi * (k + 1.5) / sections);
    const double a = angle(rng);
    EXPECT_NEAR(dummy.surface_radius(h, a), expected, 1e-13);
    // ... inside the true sphere (a chord), and near the equator, where the chords are steep,
    // within about the sag R (1 - cos(pi / 2 sections)) of it
    const double exact = std::sqrt(R * R - (h - c.y()) * (h - c.y()));
    EXPECT_GE(exact - expected, -1e-15);
    if (std::abs(h - c.y()) < 0.5 * R) {
      EXPECT_LE(exact - expected, 1.25 * R * (1.0 - std::cos(kPi / (2 * sections))));
    }
    const auto at = [&](double r) {
      return Vec3(c.x() + r * std::sin(a), h, c.z() + r * std::cos(a));
    };
    EXPECT_TRUE(dummy.inside(at(expected * (1.0 - 1e-6))));
    EXPECT_FALSE(dummy.inside(at(expected * (1.0 + 1e-6))));
  }
  EXPECT_FALSE(dummy.inside(c + Vec3(0.0, R, 0.0)));  // above the top section
}

TEST(Dummy, InsideIrregularMatchesSurfaceRadius) {
  // Points on both sides of a non-circular, off-centre surface, where the cheap radius bounds
  // do not decide and the angle is needed.
  const Dummy dummy(dress_form_sections(80, 32));
  const auto& y = dummy.sections().y;
  std::mt19937 rng(6);
  std::uniform_real_distribution<double> angle(-kPi, kPi), height(y.back(), y.front());
  for (int i = 0; i < 5000; ++i) {
    const double a = angle(rng), h = height(rng);
    const double r = dummy.surface_radius(h, a);
    const Eigen::Vector2d axis = dummy.axis_at(h);
    for (double f : {0.5, 0.999, 1.001, 1.5}) {
      const Vec3 p(axis.x() + f * r * std::sin(a), h, axis.y() + f * r * std::cos(a));
      EXPECT_EQ(dummy.inside(p), f < 1.0) << "f = " << f << " h = " << h << " a = " << a;
    }
  }
}

// nearest(), nearest_within() against the brute-force oracle on points near the surface
// (around random object particles) and far from it.
void expect_queries_match_brute_force(const Dummy& dummy, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_int_distribution<int> particle(0, dummy.size() - 1);
  const Eigen::Map<const Eigen::Matrix3Xd> pos(dummy.positions().data(), 3, dummy.size());
  const Vec3 lo = pos.rowwise().minCoeff(), hi = pos.rowwise().maxCoeff();
  const Vec3 mid = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
  for (int i = 0; i < 6000; ++i) {
    Vec3 p;
    switch (i % 4) {
      case 0:  // within a few millimetres of the surface
        p = dummy.position(particle(rng)) + 0.006 * Vec3(u(rng), u(rng), u(rng));
        break;
      case 1:  // within a few centimetres
        p = dummy.position(particle(rng)) + 0.04 * Vec3(u(rng), u(rng), u(rng));
        break;
      case 2:  // anywhere in the bounding box grown by half a metre
        p = mid + (half + Vec3::Constant(0.5)).cwiseProduct(Vec3(u(rng), u(rng), u(rng)));
        break;
      default:  // far away
        p = mid + 10.0 * Vec3(u(rng), u(rng), u(rng));
    }
    const NearestObjectParticle expected = dummy.nearest_brute_force(p);
    ASSERT_GE(expected.index, 0);
    const NearestObjectParticle got = dummy.nearest(p);
    ASSERT_EQ(got.index, expected.index) << "p = " << p.transpose();
    ASSERT_EQ(got.distance, expected.distance);
    EXPECT_NEAR(expected.distance, (dummy.position(expected.index) - p).norm(), 1e-15);
    for (double radius : {0.005, 0.01, 0.015, 0.05, 0.3}) {
      const NearestObjectParticle within = dummy.nearest_within(p, radius);
      if (expected.distance < radius) {
        ASSERT_EQ(within.index, expected.index) << "p = " << p.transpose() << " r = " << radius;
        ASSERT_EQ(within.distance, expected.distance);
      } else {
        ASSERT_EQ(within.index, -1) << "p = " << p.transpose() << " r = " << radius;
      }
    }
  }
}

TEST(Dummy, NearestMatchesBruteForceOnDressForm) {
  expect_queries_match_brute_force(Dummy(dress_form_sections(80, 32)), 7);
}

TEST(Dummy, NearestMatchesBruteForceOnCylinder) {
  expect_queries_match_brute_force(Dummy(cylinder_sections(0.12, 0.1, 0.0, 1.3, 0.7, 80, 32)), 8);
}

TEST(Dummy, NearestMatchesBruteForceOnSphere) {
  expect_queries_match_brute_force(Dummy(sphere_sections(0.2, Vec3(0.0, 1.0, 0.1), 40, 32)), 9);
}

TEST(Dummy, NearestMatchesBruteForceOnIrregularStack) {
  expect_queries_match_brute_force(Dummy(irregular_sections(50, 20, 10)), 11);
}

TEST(Dummy, NearestWithinRejectsNonPositiveRadius) {
  const Dummy dummy(cylinder_sections(0.1, 0.0, 0.0, 1.0, 0.0, 5, 8));
  EXPECT_EQ(dummy.nearest_within(dummy.position(3), 0.0).index, -1);
  const NearestObjectParticle on = dummy.nearest_within(dummy.position(3), 1e-9);
  EXPECT_EQ(on.index, 3);
  EXPECT_EQ(on.distance, 0.0);
}

TEST(Dummy, NonFinitePointsHaveNoContact) {
  // A diverging run hands NaN and inf to every query before its step ends: none may become an
  // array index (a NaN angle would pick a radius column).
  const Dummy dummy(irregular_sections(50, 20, 12));
  const double nan = std::nan(""), inf = INFINITY;
  for (const Vec3& p : {Vec3(nan, 1.2, 0.0), Vec3(0.0, nan, 0.0), Vec3(0.0, 1.2, nan),
                        Vec3(inf, 1.2, 0.0), Vec3(0.0, -inf, 0.0), Vec3(nan, nan, nan)}) {
    EXPECT_EQ(dummy.nearest_within(p, 0.1).index, -1);
    EXPECT_EQ(dummy.nearest(p).index, -1);
    EXPECT_FALSE(dummy.inside(p));
    EXPECT_FALSE(dummy.surface_gap(p).has_value());
    EXPECT_EQ(dummy.outside_margin(p), 0.0);
    std::vector<int> near;
    dummy.particles_within(p, 0.1, near);
    EXPECT_TRUE(near.empty());
  }
  EXPECT_TRUE(std::isfinite(dummy.surface_radius(1.2, nan)));
  EXPECT_TRUE(std::isfinite(dummy.surface_radius(nan, 0.3)));
}

}  // namespace
}  // namespace drape
