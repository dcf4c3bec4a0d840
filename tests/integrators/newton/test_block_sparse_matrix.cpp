// The block-row matrix against the same matrix held densely; its Gauss-Seidel sweeps against
// the single-precision symmetric copy they read, formed from the blocks right of the diagonal
// (block_sparse_matrix.hpp).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <stdexcept>

#include "integrators/newton/block_sparse_matrix.hpp"
#include "tests/support/grid_matrix.hpp"
#include "tests/support/test_support.hpp"

namespace drape {
namespace {

// A 4-node chain with one long link (0, 3), random blocks.
detail::BlockSparseMatrix chain(Eigen::MatrixXd& dense) {
  detail::BlockSparseMatrix a;
  a.set_pattern({{1, 3}, {0, 2}, {1}, {0}});
  dense = Eigen::MatrixXd::Zero(12, 12);
  const Eigen::VectorXd values =
      testing::jitter(Eigen::VectorXd::Zero(9 * a.row_start(a.rows())), 1.0, 3);
  for (int i = 0; i < a.rows(); ++i)
    for (int k = a.row_start(i); k < a.row_start(i + 1); ++k) {
      Mat3 block = Eigen::Map<const Mat3>(values.data() + 9 * k);
      // Diagonal blocks strongly dominant, so that Gauss-Seidel's inverses exist.
      if (a.column(k) == i) block += 10.0 * Mat3::Identity();
      a.blocks()[static_cast<std::size_t>(k)] = block;
      dense.block<3, 3>(3 * i, 3 * a.column(k)) = block;
    }
  a.finish_rows(true);
  return a;
}

TEST(BlockSparseMatrix, PatternKeepsTheDiagonalFirstAndFindsBlocks) {
  Eigen::MatrixXd dense;
  const detail::BlockSparseMatrix a = chain(dense);
  EXPECT_EQ(a.rows(), 4);
  EXPECT_EQ(a.row_start(4), 10);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(a.column(a.row_start(i)), i);
  EXPECT_EQ(a.find(0, 3), 2);
  EXPECT_EQ(a.find(3, 0), 9);
  EXPECT_EQ(a.find(0, 2), -1);
}

TEST(BlockSparseMatrix, ProductAndSweepsMatchTheDenseMatrix) {
  Eigen::MatrixXd dense;
  const detail::BlockSparseMatrix a = chain(dense);
  const Eigen::VectorXd p = testing::jitter(Eigen::VectorXd::Zero(12), 1.0, 4);
  const Eigen::VectorXd b = testing::jitter(Eigen::VectorXd::Zero(12), 1.0, 5);
  Eigen::VectorXd out;
  a.multiply(p, out);
  EXPECT_LT((out - dense * p).norm(), 1e-13 * out.norm());

  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(12, 12);
  for (int i = 0; i < 4; ++i) d.block<3, 3>(3 * i, 3 * i) = dense.block<3, 3>(3 * i, 3 * i);
  a.precondition_jacobi(b, out);
  EXPECT_LT((d * out - b).norm(), 1e-13 * b.norm());

  // The sweeps' matrix (testing::sweep_matrix), split by blocks: D the diagonal blocks, L and U
  // the blocks below and above them (U = L' exactly).
  const Eigen::MatrixXd sweeps = testing::sweep_matrix(dense);
  Eigen::MatrixXd l = Eigen::MatrixXd::Zero(12, 12), u = l;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      (i == j ? d : i > j ? l : u).block<3, 3>(3 * i, 3 * j) = sweeps.block<3, 3>(3 * i, 3 * j);
  EXPECT_EQ(u, l.transpose());
  // Off the diagonal the copy is the blocks right of the diagonal up to float's rounding, 2^-24
  // relative, mirrored left of it (the chain's blocks are not symmetric: the mirrors are not
  // the matrix's own left blocks).
  Eigen::MatrixXd right = dense;
  for (int i = 0; i < 4; ++i) right.block(3 * i, 0, 3, 3 * i + 3).setZero();
  EXPECT_LE((u - right).cwiseAbs().maxCoeff(), 0x1p-24 * right.cwiseAbs().maxCoeff());
  // A backward sweep solves (D + U) x_new = b - L x_old; the forward one from zero
  // (D + L) x = b, and its residual is b - (D + L + U) x.
  Eigen::VectorXd x = p, residual;
  a.backward_sweep(b, x);
  EXPECT_LT(((d + u) * x - (b - l * p)).norm(), 1e-12 * b.norm());
  a.forward_sweep_from_zero(b, x, residual);
  EXPECT_LT(((d + l) * x - b).norm(), 1e-12 * b.norm());
  EXPECT_LT((residual - (b - (d + l + u) * x)).norm(), 1e-12 * b.norm());
}

TEST(BlockSparseMatrix, SweepsNeedASymmetricPattern) {
  detail::BlockSparseMatrix a;
  for (const auto& pattern : {std::vector<std::vector<int>>{{1}, {}}, {{}, {0}}}) {
    a.set_pattern(pattern);
    a.blocks()[0] = a.blocks()[2] = Mat3::Identity();
    EXPECT_THROW(a.finish_rows(true), std::logic_error);
  }
}

}  // namespace
}  // namespace drape
