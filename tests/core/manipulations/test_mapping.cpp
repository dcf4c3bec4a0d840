// Mapping (docs/model.md section 7) against its closed form on a cylinder and on a cone.
#include <gtest/gtest.h>

#include <cmath>

#include "core/dummy/dummy_sources.hpp"
#include "core/manipulations/mapping.hpp"

namespace drape {
namespace {

// Expected mapped position on a stack whose section at height h has radius radius(h), centred
// on the y axis shifted by (cx, cz): the polygon of the section above has chords of length
// 2 R_above sin(pi/P); the angle is linear along each chord.
Vec3 closed_form(double radius_above, double radius_here, double cx, double cz, int points,
                 double height, double arc, int direction, double delta) {
  const double chord = 2.0 * radius_above * std::sin(M_PI / points);
  const double edges = arc / chord;  // whole chords plus the fraction of the last one
  const double theta = direction * edges * 2.0 * M_PI / points;
  const double r = radius_here + delta;
  return Vec3(cx + r * std::sin(theta), height, cz + r * std::cos(theta));
}

TEST(Mapping, CylinderMatchesTheClosedFormForEveryParticle) {
  const double R = 0.15, cx = 0.02, cz = -0.01, delta = 0.008;
  const Dummy dummy(cylinder_sections(R, cx, cz, 1.4, 0.8, 61, 32));
  ClothParams p;
  p.rows = 12;
  p.cols = 40;  // 0.8 m: more than the girth, so the walk wraps round
  p.spacing = 0.02;
  p.particle_mass = 1e-4;
  p.k_structural = 10;
  const Cloth cloth = build_cloth(p);
  for (const int direction : {1, -1}) {
    const Eigen::VectorXd x = map_cloth(cloth, dummy, 1.3, direction, delta);
    for (int i = 0; i < cloth.size(); ++i) {
      const int r = cloth.row_of(i), c = cloth.col_of(i);
      const Vec3 expected =
          closed_form(R, R, cx, cz, 32, 1.3 - r * 0.02, c * 0.02, direction, delta);
      EXPECT_LT((x.segment<3>(3 * i) - expected).norm(), 1e-12) << "row " << r << " col " << c;
    }
  }
}

TEST(Mapping, DirectionPlusOneGoesTowardsPlusX) {
  const Dummy dummy(cylinder_sections(0.1, 0.0, 0.0, 1.0, 0.0, 11, 16));
  const MappedPoint m = map_particle(dummy, 0, 3, 0.02, 0.9, 1, 0.01);
  EXPECT_GT(m.position.x(), 0.0);
  EXPECT_GT(m.angle, 0.0);
  EXPECT_NEAR(map_particle(dummy, 0, 0, 0.02, 0.9, 1, 0.01).position.x(), 0.0, 1e-15)
      << "column 0 lies on the centre line";
}

TEST(Mapping, ConeUsesThePolygonAboveAndTheRadiusInterpolatedInHeight) {
  // Radius 0.10 m at y = 1.0 growing to 0.20 m at y = 0.0, 11 sections every 0.1 m.
  DummySections s;
  const int points = 24;
  s.radius.resize(11, points);
  for (int k = 0; k < 11; ++k) {
    s.y.push_back(1.0 - 0.1 * k);
    s.cx.push_back(0.0);
    s.cz.push_back(0.0);
    s.radius.row(k).setConstant(0.10 + 0.01 * k);
  }
  const Dummy dummy(s);
  const double height = 0.74;  // between the sections at 0.8 (above, R = 0.12) and 0.7
  const MappedPoint m = map_particle(dummy, 3, 5, 0.02, height + 3 * 0.02, 1, 0.005);
  const Vec3 expected = closed_form(0.12, 0.126, 0.0, 0.0, points, height, 0.1, 1, 0.005);
  EXPECT_NEAR(m.height, height, 1e-15);
  EXPECT_NEAR(m.radius, 0.126, 1e-12);
  EXPECT_LT((m.position - expected).norm(), 1e-12);
}

}  // namespace
}  // namespace drape
