#pragma once
// A random matrix with the shape of the reduced system S of a spring grid
// (reduced_newton_solver.hpp), shared by the multigrid tests and the linear-solver benchmarks,
// the dense matrix it is and the one its sweeps see; no test framework needed.
#include <Eigen/Dense>
#include <random>
#include <vector>

#include "integrators/linear/symmetric_block_matrix.hpp"

namespace drape::testing {

/// 0.01 I + sum over the rows x cols grid's pairs of nodes at most `reach` rows and columns
/// apart (the 8 neighbours for 1; 2 spans bending springs' pattern) of a random SPD coupling
/// C = R R' (R's entries uniform in [-1, 1], drawn in pair order from `seed`): C on both
/// diagonal blocks and -C off them. Its diagonal is inverted.
inline detail::SymmetricBlockMatrix grid_matrix(int rows, int cols, unsigned seed, int reach = 1) {
  const int n = rows * cols;
  std::vector<std::vector<int>> neighbours(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i)
    for (int dr = -reach; dr <= reach; ++dr)
      for (int dc = -reach; dc <= reach; ++dc) {
        const int r = i / cols + dr, c = i % cols + dc;
        if ((dr != 0 || dc != 0) && r >= 0 && r < rows && c >= 0 && c < cols)
          neighbours[static_cast<std::size_t>(i)].push_back(r * cols + c);
      }
  detail::SymmetricBlockMatrix a;
  a.set_pattern(neighbours);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < n; ++i)
    for (const int j : neighbours[static_cast<std::size_t>(i)]) {
      if (j < i) continue;
      Mat3 r;
      for (int k = 0; k < 9; ++k) r.data()[k] = u(rng);  // column-major, as the tests drew it
      const detail::PackedBlock c = detail::pack(r * r.transpose());
      a.blocks()[static_cast<std::size_t>(a.find(i, j))] -= c;
      a.blocks()[static_cast<std::size_t>(a.row_start(i))] += c;
      a.blocks()[static_cast<std::size_t>(a.row_start(j))] += c;
    }
  for (int i = 0; i < n; ++i)
    a.blocks()[static_cast<std::size_t>(a.row_start(i))] += detail::pack(0.01 * Mat3::Identity());
  a.finish_rows();
  return a;
}

/// `a` as a dense matrix, column by column through its product.
inline Eigen::MatrixXd dense_matrix(const detail::SymmetricBlockMatrix& a) {
  const Eigen::Index n3 = 3 * static_cast<Eigen::Index>(a.rows());
  Eigen::MatrixXd out(n3, n3);
  Eigen::VectorXd column;
  for (Eigen::Index k = 0; k < n3; ++k) {
    a.multiply(Eigen::VectorXd::Unit(n3, k), column);
    out.col(k) = column;
  }
  return out;
}

/// The dense matrix the Gauss-Seidel sweeps of `a` (held densely) see (symmetric_block_matrix.hpp):
/// `a` off the diagonal, and on it the inverses of the symmetric parts of the diagonal blocks'
/// inverses (the blocks themselves up to round-off).
inline Eigen::MatrixXd sweep_matrix(const Eigen::MatrixXd& a) {
  Eigen::MatrixXd out = a;
  for (Eigen::Index i = 0; i < a.rows() / 3; ++i) {
    const Mat3 inverse = a.block<3, 3>(3 * i, 3 * i).inverse();
    out.block<3, 3>(3 * i, 3 * i) = (0.5 * (inverse + inverse.transpose())).inverse();
  }
  return out;
}

}  // namespace drape::testing
