// The multigrid V-cycle on random SPD block matrices with the cloth's 9-point grid pattern: an
// exact solve on a coarsest-size grid, symmetric positive definite, and a convergent iteration.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <functional>

#include "integrators/newton/aggregation_multigrid.hpp"
#include "tests/support/test_support.hpp"

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

TEST(AggregationMultigrid, PreconditionedSpectrumIsPositiveAndNarrow) {
  // The eigenvalues of B A (those of L' B L for A = L L') on a 3-level grid: all positive,
  // and a condition number far below block Jacobi's, which is what cuts CG's iterations.
  const int n = 12;
  const detail::BlockSparseMatrix a = grid_matrix(n, n, 7);
  detail::AggregationMultigrid mg;
  mg.build(a, n, n);
  mg.update(a);
  ASSERT_EQ(mg.levels(), 3);
  const Eigen::Index n3 = 3 * n * n;
  Eigen::MatrixXd dense_a(n3, n3);
  Eigen::VectorXd column;
  for (Eigen::Index k = 0; k < n3; ++k) {
    a.multiply(Eigen::VectorXd::Unit(n3, k), column);
    dense_a.col(k) = column;
  }
  const Eigen::MatrixXd l = dense_a.llt().matrixL();
  auto condition = [&](const std::function<void(const Eigen::VectorXd&, Eigen::VectorXd&)>& b) {
    Eigen::MatrixXd lbl(n3, n3);
    for (Eigen::Index k = 0; k < n3; ++k) {
      b(l.col(k), column);
      lbl.col(k) = l.transpose() * column;
    }
    const Eigen::VectorXd eigenvalues =
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(0.5 * (lbl + lbl.transpose()),
                                                      Eigen::EigenvaluesOnly)
            .eigenvalues();
    EXPECT_GT(eigenvalues.minCoeff(), 0.0);
    return eigenvalues.maxCoeff() / eigenvalues.minCoeff();
  };
  const double multigrid = condition([&](const Eigen::VectorXd& r, Eigen::VectorXd& out) {
    mg.apply(a, r, out);
  });
  const double jacobi = condition([&](const Eigen::VectorXd& r, Eigen::VectorXd& out) {
    a.precondition_jacobi(r, out);
  });
  // Measured: 6.0 against 1350.
  EXPECT_LT(multigrid, 10.0);
  EXPECT_GT(jacobi, 100.0 * multigrid);
}

}  // namespace
}  // namespace drape
