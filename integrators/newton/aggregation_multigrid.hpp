#pragma once
// An aggregation multigrid cycle on the cloth grid: the preconditioner of CG on the reduced
// system S (`pcg-multigrid`).
//
// Each coarsening joins 2x2 neighbouring grid nodes into one aggregate; the prolongation P
// copies an aggregate's 3-vector to its nodes (piecewise constant), and the coarse operator is
// Galerkin's A_c = P^T A P, i.e. the sum of the fine 3x3 blocks between two aggregates. With
// the grid's spring offsets inside an aggregate's neighbours, every level keeps the fine
// pattern's shape, and forming the coarse values is one pass of block additions through a map
// built once. The cycle smooths with one forward block Gauss-Seidel sweep before the coarse
// correction (scaled by a constant over-correction factor) and one backward sweep after it,
// and solves the coarsest level (at most 16 nodes) by a dense Cholesky factorisation; every
// grid below the finest solves its coarse equation by two such cycles (a W-cycle below a
// V-cycle at the finest grid), whose error propagation is the square of one's. The
// preconditioner B is then symmetric, and positive definite for SPD A: with G the forward
// sweep's error propagation (an A-norm contraction, Gauss-Seidel on SPD A) and C >= 0 the
// scaled coarse correction, I - BA = G' (I - C A) G has A-norm energy below |G e|_A^2 < |e|_A^2,
// so BA's eigenvalues are positive, as CG needs. (One cycle on a coarse grid has B_c A_c's
// eigenvalues lam in (0, 2); two have 1 - (1 - lam)^2 in (0, 1], so C A stays in [0, 1.5].)
// Vanek, Mandel and Brezina 1996 (Computing 56, unsmoothed aggregation); Trottenberg,
// Oosterlee and Schuller 2001 ("Multigrid", section 2.4 on symmetric cycles).
#include <Eigen/Cholesky>
#include <vector>

#include "integrators/newton/block_sparse_matrix.hpp"

namespace drape::detail {

/// One multigrid cycle (V at the finest grid, W below) as a symmetric positive definite
/// preconditioner.
class AggregationMultigrid {
 public:
  /// Builds the levels for `fine`, whose row i is node i of a rows x cols grid (row-major).
  void build(const BlockSparseMatrix& fine, int rows, int cols);
  /// Forms the coarse operators from `fine`'s current values and factorises the coarsest.
  /// `fine` must have its diagonal inverted (BlockSparseMatrix::invert_diagonal).
  void update(const BlockSparseMatrix& fine);
  /// out = B r, B the cycle started from zero.
  void apply(const BlockSparseMatrix& fine, const Eigen::VectorXd& r, Eigen::VectorXd& out);
  /// Number of grids, the fine one included.
  int levels() const { return static_cast<int>(m_levels.size()) + 1; }

 private:
  /// A grid coarser than the one before it.
  struct Level {
    BlockSparseMatrix matrix;
    std::vector<int> aggregate;  // node of the finer grid -> node of this one
    std::vector<int> entry;      // block of the finer matrix -> block of this one it adds to
    Eigen::VectorXd b, x, finer_residual;
    Eigen::VectorXd remainder, correction;  // the second cycle's right-hand side and result
  };

  void cycle(const BlockSparseMatrix& a, std::size_t next, const Eigen::VectorXd& b,
             Eigen::VectorXd& x);

  std::vector<Level> m_levels;
  Eigen::LLT<Eigen::MatrixXd> m_coarsest;
};

}  // namespace drape::detail
