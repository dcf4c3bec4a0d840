#pragma once
// A matrix of 3x3 blocks stored by block rows (BSR): the reduced system S and the coarse levels
// of its multigrid preconditioner. Each row keeps its diagonal block first, then its
// off-diagonal blocks, so that a product or a Gauss-Seidel sweep streams through one row's
// blocks contiguously (no scatter, unlike a loop over springs).
//
// The Gauss-Seidel sweeps read a single-precision copy of the blocks (docs/performance.md,
// "Single-precision sweeps"): a multigrid cycle reads the fine matrix twice and CG's product
// once, so at 128 x 128 (10.6 MB of double blocks) a CG iteration streams about 32 MB, and the
// step's cost per particle grew with the grid once that no longer stayed in the cache. The
// sweeps only precondition: CG's product and residuals stay in double, so the solution's accuracy
// is CG's tolerance, not float's. The copy takes each pair of off-diagonal blocks from the one
// right of the diagonal (its transpose left of it) and the symmetric part of D_i^-1, so that the
// cycle is exactly symmetric (CG needs a symmetric preconditioner) where the double blocks are
// transposes only to round-off: S's couplings -C_e are symmetric up to the rounding of their
// products, and the Galerkin diagonal blocks sum their terms in another order than their
// transposes would (the coarse blocks left of the diagonal are written as exact transposes).
// Within that round-off the copy is A rounded to float.
//
// A row is finished (its diagonal inverted, its share of the copy written) by finish_row() as
// soon as its diagonal and right blocks hold their values, so that an assembly writing row by
// row does it while the row is in cache instead of in two more passes over the matrix
// (docs/performance.md, "Assembling S row by row").
#include <vector>

#include "core/model/state.hpp"

namespace drape::detail {

/// A square matrix of 3x3 blocks with a fixed pattern that always holds the diagonal.
class BlockSparseMatrix {
 public:
  /// Sets the pattern: `neighbours[i]` lists the columns of row i other than i, without
  /// duplicates. Every block becomes zero.
  void set_pattern(const std::vector<std::vector<int>>& neighbours);
  /// Number of block rows.
  int rows() const { return static_cast<int>(m_row_start.size()) - 1; }
  /// Index of block (i, j) in blocks(), or -1 when (i, j) is not in the pattern.
  int find(int i, int j) const;
  /// Block row i occupies blocks()[row_start(i)] (its diagonal) to blocks()[row_start(i + 1) - 1].
  int row_start(int i) const { return m_row_start[static_cast<std::size_t>(i)]; }
  int column(int k) const { return m_column[static_cast<std::size_t>(k)]; }
  /// Index of block (j, i) for block k = (i, j), or -1 when (j, i) is not in the pattern.
  int transpose(int k) const { return m_transpose[static_cast<std::size_t>(k)]; }
  /// True when every block (i, j) of the pattern has its (j, i).
  bool symmetric_pattern() const { return m_symmetric_pattern; }
  std::vector<Mat3>& blocks() { return m_blocks; }
  const std::vector<Mat3>& blocks() const { return m_blocks; }

  /// out = A p.
  void multiply(const Eigen::VectorXd& p, Eigen::VectorXd& out) const;
  /// Inverts row i's diagonal block (for precondition_jacobi() and the sweeps; it must be
  /// invertible, symmetric positive definite for an SPD matrix) and, with `sweeps`, writes row
  /// i's share of the sweeps' single-precision copy: D_i^-1's symmetric part and the blocks right
  /// of the diagonal, with their transposes at the mirrors left of it (in rows below). Needs row
  /// i's diagonal and right blocks final; with `sweeps`, a symmetric pattern.
  void finish_row(int i, bool sweeps);
  /// finish_row() for every row.
  void finish_rows(bool sweeps);
  /// out = D^-1 r, D the block diagonal.
  void precondition_jacobi(const Eigen::VectorXd& r, Eigen::VectorXd& out) const;
  /// One block Gauss-Seidel sweep on A x = b with rows descending:
  /// x = (D + U)^-1 (b - L x), L and U the blocks left and right of the diagonal (of the
  /// single-precision copy, see above).
  void backward_sweep(const Eigen::VectorXd& b, Eigen::VectorXd& x) const;
  /// The forward sweep (rows ascending) from x = 0, x = (D + L)^-1 b, and the residual it
  /// leaves, b - A x = -U x, A here the single-precision copy the sweeps read: together one pass
  /// over the blocks instead of a sweep and a product, each row's residual formed as soon as
  /// the x it reads is final. `residual` must not alias `b` or `x` (it is written while later
  /// rows of b are still read).
  void forward_sweep_from_zero(const Eigen::VectorXd& b, Eigen::VectorXd& x,
                               Eigen::VectorXd& residual) const;

 private:
  std::vector<int> m_row_start{0}, m_column;  // row_start of an empty matrix: rows() = 0
  std::vector<int> m_upper_start;  // row i's first block right of the diagonal
  int m_upper_reach = 0;           // the largest column - row of a block right of the diagonal
  std::vector<int> m_transpose;    // index of block (j, i) for block (i, j), -1 if none
  bool m_symmetric_pattern = true;
  std::vector<Mat3> m_blocks, m_diagonal_inverse;
  // The sweeps' copy, indexed as m_blocks: D_i^-1 at row_start(i), the off-diagonal blocks after.
  std::vector<Eigen::Matrix3f> m_sweep_blocks;
};

}  // namespace drape::detail
