// The multigrid V-cycle on random SPD block matrices with the cloth's 9-point grid pattern: an
// exact solve on a coarsest-size grid, symmetric positive definite, and a convergent iteration.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "integrators/aggregation_multigrid.hpp"
#include "test_support.hpp"

namespace drape {
namespace {

// mass I + sum over neighbour pairs of a random SPD coupling C: C on both diagonal blocks and
// -C off them, like the reduced system S of a spring grid.
detail::BlockSparseMatrix grid_matrix(int rows, int cols, unsigned seed) {
  const int n = rows * cols;
  std::vector<std::vector<int>> neighbours(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i)
    for (int dr = -1; dr <= 1; ++dr)
      for (int dc = -1; dc <= 1; ++dc) {
        const int r = i / cols + dr, c = i % cols + dc;
        if ((dr != 0 || dc != 0) && r >= 0 && r < rows && c >= 0 && c < cols)
          neighbours[static_cast<std::size_t>(i)].push_back(r * cols + c);
      }
  detail::BlockSparseMatrix a;
  a.set_pattern(neighbours);
  const Eigen::VectorXd values = testing::jitter(Eigen::VectorXd::Zero(9 * 8 * n), 1.0, seed);
  int pair = 0;
  for (int i = 0; i < n; ++i)
    for (const int j : neighbours[static_cast<std::size_t>(i)]) {
      if (j < i) continue;
      const Mat3 r = Eigen::Map<const Mat3>(values.data() + 9 * pair++);
      const Mat3 c = r * r.transpose();
      a.blocks()[static_cast<std::size_t>(a.find(i, j))] -= c;
      a.blocks()[static_cast<std::size_t>(a.find(j, i))] -= c;
      a.blocks()[static_cast<std::size_t>(a.row_start(i))] += c;
      a.blocks()[static_cast<std::size_t>(a.row_start(j))] += c;
    }
  for (int i = 0; i < n; ++i)
    a.blocks()[static_cast<std::size_t>(a.row_start(i))] += 0.01 * Mat3::Identity();
  a.invert_diagonal();
  return a;
}

Eigen::VectorXd cycle(detail::AggregationMultigrid& mg, const detail::BlockSparseMatrix& a,
                      const Eigen::VectorXd& r) {
  Eigen::VectorXd out;
  mg.apply(a, r, out);
  return out;
}

TEST(AggregationMultigrid, SolvesExactlyOnACoarsestSizeGrid) {
  const detail::BlockSparseMatrix a = grid_matrix(4, 4, 1);
  detail::AggregationMultigrid mg;
  mg.build(a, 4, 4);
  mg.update(a);
  EXPECT_EQ(mg.levels(), 1);
  const Eigen::VectorXd b = testing::jitter(Eigen::VectorXd::Zero(48), 1.0, 2);
  Eigen::VectorXd product;
  a.multiply(cycle(mg, a, b), product);
  EXPECT_LT((product - b).norm(), 1e-10 * b.norm());
}

TEST(AggregationMultigrid, IsSymmetricPositiveDefinite) {
  struct Grid {
    int rows, cols, levels;
  };
  // 20x20 -> 10x10 -> 5x5 -> 3x3; 7x5 -> 4x3 (odd sizes: edge aggregates of one or two nodes).
  for (const Grid g : {Grid{20, 20, 4}, Grid{7, 5, 2}}) {
    const detail::BlockSparseMatrix a = grid_matrix(g.rows, g.cols, 3);
    detail::AggregationMultigrid mg;
    mg.build(a, g.rows, g.cols);
    mg.update(a);
    EXPECT_EQ(mg.levels(), g.levels);
    const Eigen::Index n3 = 3 * g.rows * g.cols;
    for (unsigned seed = 0; seed < 5; ++seed) {
      const Eigen::VectorXd z1 = testing::jitter(Eigen::VectorXd::Zero(n3), 1.0, 10 + seed);
      const Eigen::VectorXd z2 = testing::jitter(Eigen::VectorXd::Zero(n3), 1.0, 20 + seed);
      const Eigen::VectorXd b1 = cycle(mg, a, z1), b2 = cycle(mg, a, z2);
      EXPECT_NEAR(z1.dot(b2), z2.dot(b1), 1e-12 * z1.norm() * b2.norm());
      EXPECT_GT(z1.dot(b1), 0.0);
    }
  }
}

TEST(AggregationMultigrid, IteratedCycleConverges) {
  // x += B (b - A x) converges because the cycle approximates A^-1 (a convergence factor of
  // about 0.7 a cycle on this random matrix, independent of the grid size).
  const detail::BlockSparseMatrix a = grid_matrix(32, 32, 5);
  detail::AggregationMultigrid mg;
  mg.build(a, 32, 32);
  mg.update(a);
  const Eigen::VectorXd b = testing::jitter(Eigen::VectorXd::Zero(3 * 32 * 32), 1.0, 6);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(b.size()), product;
  for (int k = 0; k < 20; ++k) {
    a.multiply(x, product);
    x += cycle(mg, a, b - product);
  }
  a.multiply(x, product);
  EXPECT_LT((b - product).norm(), 1e-2 * b.norm());
}

}  // namespace
}  // namespace drape
