#pragma once
// A geometric multigrid cycle on the cloth grid: the preconditioner of CG on the reduced
// system S (`pcg-multigrid`).
//
// Each coarser grid keeps every second node of the finer one in both directions (a rows x cols
// grid has (rows + 1) / 2 x (cols + 1) / 2 coarse nodes at the even rows and columns). The
// prolongation P interpolates bilinearly: a fine node on a coarse node copies it, one between
// two coarse nodes takes their mean, one in a cell's middle the mean of its four corners (a
// fine node past the last coarse row or column, on an even-sized grid, copies its one coarse
// neighbour). The coarse operator is Galerkin's A_c = P^T A P; bilinear P keeps the fine
// grid's 9-point pattern (3x3 neighbours) on every coarse grid, and a wider fine pattern stays
// bounded (the pattern is built from P, not assumed). Forming the coarse values is one pass of
// weighted block additions through a list built once.
//
// The cycle smooths with one forward block Gauss-Seidel sweep before the coarse correction and
// one backward sweep after it, and solves the coarsest level (at most 16 nodes) by a dense
// Cholesky factorisation. The preconditioner B is symmetric (restriction is P^T, the two sweeps
// are each other's adjoints) and positive definite for SPD A: with G the forward sweep's error
// propagation (an A-norm contraction, Gauss-Seidel on SPD A) and the coarse correction an
// A-orthogonal projection (exact coarsest solve) or a contraction (a coarse cycle), the error
// propagation I - BA = G' (I - P B_c P^T A) G has A-norm below one, so BA's eigenvalues lie in
// (0, 1]. Unlike piecewise-constant aggregation (the cycle this replaced, docs/performance.md
// "Implicit steps at 1/30 s"), interpolation of first order is what makes a V-cycle's
// convergence independent of the number of grids for an operator of second order: Trottenberg,
// Oosterlee and Schuller 2001 ("Multigrid", sections 2.3 to 2.5 and 3.3 on Galerkin coarse
// operators with bilinear interpolation).
#include <Eigen/Cholesky>
#include <vector>

#include "integrators/newton/block_sparse_matrix.hpp"

namespace drape::detail {

/// One multigrid V-cycle as a symmetric positive definite preconditioner.
class GridMultigrid {
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
  /// One term of A_c = P^T A P: coarse block `coarse` += weight * fine block `fine`.
  struct GalerkinTerm {
    int fine, coarse;
    double weight;
  };
  /// A grid coarser than the one before it.
  struct Level {
    BlockSparseMatrix matrix;
    // P's rows: finer node i interpolates from parent[k] with weight[k],
    // k in [parent_start[i], parent_start[i + 1]).
    std::vector<int> parent_start, parent;
    std::vector<double> weight;
    std::vector<GalerkinTerm> galerkin;
    Eigen::VectorXd b, x, finer_residual, remainder, correction;
  };

  void cycle(const BlockSparseMatrix& a, std::size_t next, const Eigen::VectorXd& b,
             Eigen::VectorXd& x);

  std::vector<Level> m_levels;
  Eigen::LLT<Eigen::MatrixXd> m_coarsest;
};

}  // namespace drape::detail
