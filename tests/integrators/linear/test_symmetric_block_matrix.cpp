// The symmetric block matrix against the same matrix held densely, its Gauss-Seidel sweeps
// against the dense matrix they see (symmetric_block_matrix.hpp).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <stdexcept>

#include "core/parallel/parallel_for.hpp"
#include "integrators/linear/symmetric_block_matrix.hpp"
#include "tests/support/grid_matrix.hpp"
#include "tests/support/test_support.hpp"

namespace drape {
namespace {

// A 4-node chain with one long link (0, 3) (listed from both ends, from one, or both), random
// symmetric blocks; `dense` receives the full matrix.
detail::SymmetricBlockMatrix chain(Eigen::MatrixXd& dense) {
  detail::SymmetricBlockMatrix a;
  a.set_pattern({{1, 3}, {0, 2}, {}, {0}});
  dense = Eigen::MatrixXd::Zero(12, 12);
  const Eigen::VectorXd values =
      testing::jitter(Eigen::VectorXd::Zero(9 * a.row_start(a.rows())), 1.0, 3);
  for (int i = 0; i < a.rows(); ++i)
    for (int k = a.row_start(i); k < a.row_start(i + 1); ++k) {
      const Mat3 random = Eigen::Map<const Mat3>(values.data() + 9 * k);
      Mat3 block = random + random.transpose();
      // Diagonal blocks strongly dominant, so that Gauss-Seidel's inverses exist.
      if (a.column(k) == i) block += 10.0 * Mat3::Identity();
      a.blocks()[static_cast<std::size_t>(k)] = detail::pack(block);
      dense.block<3, 3>(3 * i, 3 * a.column(k)) = block;
      dense.block<3, 3>(3 * a.column(k), 3 * i) = block;
    }
  a.finish_rows();
  return a;
}

TEST(SymmetricBlockMatrix, PacksTheSymmetricPartOfABlock) {
  const Mat3 m = Eigen::Map<const Mat3>(
      testing::jitter(Eigen::VectorXd::Zero(9), 1.0, 1).data());
  const Mat3 symmetric = 0.5 * (m + m.transpose());
  EXPECT_LT((detail::unpack(detail::pack(m)) - symmetric).cwiseAbs().maxCoeff(), 1e-15);
  const Vec3 v(0.3, -1.2, 2.0);
  EXPECT_LT((detail::times(detail::pack(m), v) - symmetric * v).norm(), 1e-15);
  EXPECT_EQ(detail::pack(symmetric), detail::pack(symmetric.transpose().eval()));
}

TEST(SymmetricBlockMatrix, APatternIgnoresSelfPairsAndRepeatsAndMayBeEmpty) {
  detail::SymmetricBlockMatrix a;
  a.set_pattern({{0, 2, 2}, {1}, {0, 0}});
  EXPECT_EQ(a.row_start(3), 4);  // the three diagonals and (0, 2)
  EXPECT_EQ(a.find(2, 0), 1);
  EXPECT_EQ(a.find(1, 0), -1);
  EXPECT_THROW(a.set_pattern({{3}, {}, {}}), std::logic_error);
  EXPECT_THROW(a.set_pattern({{-1}}), std::logic_error);
  a.set_pattern({});
  EXPECT_EQ(a.rows(), 0);
  Eigen::VectorXd out, x, scratch;
  a.multiply(Eigen::VectorXd(), out);
  a.backward_sweep(Eigen::VectorXd(), x, scratch);
  EXPECT_EQ(out.size(), 0);
  EXPECT_EQ(x.size(), 0);
}

TEST(SymmetricBlockMatrix, StoresEachPairOnceRightOfTheDiagonal) {
  Eigen::MatrixXd dense;
  const detail::SymmetricBlockMatrix a = chain(dense);
  EXPECT_EQ(a.rows(), 4);
  // Row 0: 0, 1, 3; row 1: 1, 2; rows 2 and 3: their diagonals.
  EXPECT_EQ(a.row_start(4), 7);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(a.column(a.row_start(i)), i);
  EXPECT_EQ(a.find(0, 3), 2);
  EXPECT_EQ(a.find(3, 0), 2);
  EXPECT_EQ(a.find(2, 1), a.find(1, 2));
  EXPECT_EQ(a.find(0, 2), -1);
}

TEST(SymmetricBlockMatrix, ProductAndSweepsMatchTheDenseMatrix) {
  Eigen::MatrixXd dense;
  const detail::SymmetricBlockMatrix a = chain(dense);
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
  // the blocks below and above them.
  const Eigen::MatrixXd sweeps = testing::sweep_matrix(dense);
  Eigen::MatrixXd l = Eigen::MatrixXd::Zero(12, 12), u = l;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      (i == j ? d : i > j ? l : u).block<3, 3>(3 * i, 3 * j) = sweeps.block<3, 3>(3 * i, 3 * j);
  // A backward sweep solves (D + U) x_new = b - L x_old; the forward one from zero
  // (D + L) x = b, and its residual is b - (D + L + U) x.
  Eigen::VectorXd x = p, residual, scratch;
  a.backward_sweep(b, x, scratch);
  EXPECT_LT(((d + u) * x - (b - l * p)).norm(), 1e-12 * b.norm());
  a.forward_sweep_from_zero(b, x, residual);
  EXPECT_LT(((d + l) * x - b).norm(), 1e-12 * b.norm());
  EXPECT_LT((residual - (b - (d + l + u) * x)).norm(), 1e-12 * b.norm());
}

// The sweeps of `a` (the grid's 9-point pattern, where a row's blocks reach cols + 1 rows on,
// swept in blocks of `block_rows` rows) against its dense matrix: with M = D + L_in (L_in the
// blocks below the diagonal within a sweep block; Jacobi between blocks) the forward sweep from
// zero solves M x = b and its residual is b - A x; the backward sweep solves
// M' x_new = b - (A - M') x_old.
void expect_hybrid_sweeps(const detail::SymmetricBlockMatrix& a, int block_rows) {
  const Eigen::Index n3 = 3 * static_cast<Eigen::Index>(a.rows());
  const Eigen::MatrixXd dense = testing::dense_matrix(a);
  EXPECT_EQ(dense, dense.transpose());
  const Eigen::MatrixXd sweeps = testing::sweep_matrix(dense);
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(n3, n3);  // D + L_in
  for (Eigen::Index i = 0; i < a.rows(); ++i)
    for (Eigen::Index j = (i / block_rows) * block_rows; j <= i; ++j)
      m.block<3, 3>(3 * i, 3 * j) = sweeps.block<3, 3>(3 * i, 3 * j);
  const Eigen::VectorXd b = testing::jitter(Eigen::VectorXd::Zero(n3), 1.0, 6);
  const Eigen::VectorXd old = testing::jitter(Eigen::VectorXd::Zero(n3), 1.0, 7);
  Eigen::VectorXd x, residual, scratch;
  a.forward_sweep_from_zero(b, x, residual);
  EXPECT_LT((m * x - b).norm(), 1e-12 * b.norm());
  EXPECT_LT((residual - (b - sweeps * x)).norm(), 1e-12 * b.norm());
  x = old;
  a.backward_sweep(b, x, scratch);
  const Eigen::MatrixXd mt = m.transpose();
  EXPECT_LT((mt * x - (b - (sweeps - mt) * old)).norm(), 1e-12 * b.norm());
}

TEST(SymmetricBlockMatrix, SweepsOnAGridMatchTheDenseMatrix) {
  expect_hybrid_sweeps(testing::grid_matrix(5, 7, 2), 35);  // one block: Gauss-Seidel
}

// Sweep blocks of 8 rows on the 5 x 7 grid: blocks [0, 8), ..., [32, 35).
TEST(SymmetricBlockMatrix, SweepsOverFixedBlocksAreHybridGaussSeidel) {
  detail::SymmetricBlockMatrix a = testing::grid_matrix(5, 7, 2);
  a.set_sweep_block_rows(8);
  EXPECT_THROW(a.set_sweep_block_rows(0), std::logic_error);
  expect_hybrid_sweeps(a, 8);
}

// On a 50 x 50 grid (2500 rows: the product splits its rows among the threads, the sweeps run
// as two blocks): the product is the one-thread loop's (every row gathering, then scattering to
// the rows after it) bit for bit on 1, 2 and 3 threads, and so are the sweeps.
TEST(SymmetricBlockMatrix, ThreadsGiveTheOneThreadBits) {
  const int before = thread_count();
  const detail::SymmetricBlockMatrix a = testing::grid_matrix(50, 50, 4);
  const Eigen::Index n3 = 3 * 2500;
  const Eigen::VectorXd p = testing::jitter(Eigen::VectorXd::Zero(n3), 1.0, 10);
  Eigen::VectorXd reference = Eigen::VectorXd::Zero(n3);
  for (int i = 0; i < a.rows(); ++i) {
    const Vec3 p_i = particle(p, i);
    Vec3 sum = detail::times(a.blocks()[static_cast<std::size_t>(a.row_start(i))], p_i);
    for (int k = a.row_start(i) + 1; k < a.row_start(i + 1); ++k) {
      const detail::PackedBlock& block = a.blocks()[static_cast<std::size_t>(k)];
      sum.noalias() += detail::times(block, Vec3(particle(p, a.column(k))));
      particle(reference, a.column(k)) += detail::times(block, p_i);
    }
    particle(reference, i) += sum;
  }
  Eigen::VectorXd one_forward, one_residual, one_backward;
  for (const int threads : {1, 2, 3}) {
    set_thread_count(threads);
    Eigen::VectorXd out, x, residual, scratch;
    a.multiply(p, out);
    EXPECT_EQ(out, reference) << threads << " threads";
    a.forward_sweep_from_zero(p, x, residual);
    a.backward_sweep(p, x, scratch);
    if (threads == 1) {
      one_forward = x;
      one_residual = residual;
      a.forward_sweep_from_zero(p, one_forward, one_residual);
      one_backward = x;
      continue;
    }
    EXPECT_EQ(x, one_backward) << threads << " threads";
    a.forward_sweep_from_zero(p, x, residual);
    EXPECT_EQ(x, one_forward) << threads << " threads";
    EXPECT_EQ(residual, one_residual) << threads << " threads";
  }
  set_thread_count(before);
}

}  // namespace
}  // namespace drape
