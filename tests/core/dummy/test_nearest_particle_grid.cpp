#include "core/dummy/nearest_particle_grid.hpp"

#include <gtest/gtest.h>

#include <random>

namespace drape::detail {
namespace {

GridHit brute_force(const Eigen::VectorXd& points, const Vec3& p) {
  GridHit best;
  for (int i = 0; i < points.size() / 3; ++i) {
    const double d2 = distance_squared(points.data() + 3 * i, p);
    if (best.index < 0 || d2 < best.distance_squared) best = {i, d2};
  }
  return best;
}

TEST(ParticleGrid, MatchesBruteForceOnClusteredPoints) {
  // Clusters of different densities and a thin sheet, so that cells hold from none to many.
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int n = 1500;
  Eigen::VectorXd points(3 * n);
  for (int i = 0; i < n; ++i) {
    Vec3 q = Vec3(u(rng), u(rng), u(rng));
    if (i % 3 == 0) q = Vec3(0.3, 0.2, -0.1) + 0.02 * q;
    if (i % 3 == 1) q.z() = 0.001 * q.z();
    points.segment<3>(3 * i) = q;
  }
  for (double cell : {0.01, 0.07, 0.5, 5.0}) {
    const ParticleGrid grid(points, cell);
    for (int i = 0; i < 3000; ++i) {
      const double scale = i % 2 ? 1.2 : 6.0;
      const Vec3 p = scale * Vec3(u(rng), u(rng), u(rng));
      const GridHit expected = brute_force(points, p);
      const GridHit got = grid.nearest(p);
      ASSERT_EQ(got.index, expected.index) << "cell " << cell << " p " << p.transpose();
      ASSERT_EQ(got.distance_squared, expected.distance_squared);
      for (double radius : {0.01, 0.1, 0.6}) {
        const GridHit within = grid.nearest_within(p, radius);
        ASSERT_EQ(within.index, expected.distance_squared < radius * radius ? expected.index : -1);
      }
    }
  }
}

TEST(ParticleGrid, TiesGoToTheLowestIndex) {
  Eigen::VectorXd points(12);
  points << 1, 0, 0, 0, 0, 0, 0, 0, 0, 0.5, 0.5, 0.5;  // particles 1 and 2 coincide
  const ParticleGrid grid(points, 0.1);
  EXPECT_EQ(grid.nearest(Vec3(-0.2, 0.1, 0.0)).index, 1);
  EXPECT_EQ(grid.nearest_within(Vec3(0.0, 0.0, 0.01), 0.05).index, 1);
}

TEST(ParticleGrid, ACellSizeThatUnderflowedToZeroStillBuildsAGrid) {
  // Points 1e-150 apart on one axis, none on the others, and a cell size of 0: the cell count
  // was 0 / 0 on those axes and the budget loop never ended.
  Eigen::VectorXd points(6);
  points << 0, 0, 0, 1e-150, 0, 0;
  const ParticleGrid grid(points, 0.0);
  EXPECT_EQ(grid.nearest(Vec3(1e-150, 0.0, 0.0)).index, 1);
  EXPECT_EQ(grid.nearest(Vec3(-1.0, 0.0, 0.0)).index, 0);
}

TEST(ParticleGrid, CellBudgetCapsATinyCellSize) {
  Eigen::VectorXd points(6);
  points << 0, 0, 0, 1, 1, 1;
  const ParticleGrid grid(points, 1e-9);
  const auto& d = grid.dims();
  EXPECT_LE(static_cast<double>(d[0]) * d[1] * d[2], 64.0);
  EXPECT_EQ(grid.nearest(Vec3(0.9, 0.8, 1.0)).index, 1);
}

}  // namespace
}  // namespace drape::detail
