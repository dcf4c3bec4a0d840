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
// grid's 9-point pattern (3x3 neighbours) on every coarse grid, and a wider fine pattern
// (bending springs) stays bounded at two nodes (the pattern is built from P, not assumed).
// Forming the coarse values is one pass through a list built once: each stored coarse block (on
// or right of the diagonal; A and every A_c are symmetric and stored once,
// symmetric_block_matrix.hpp) sums its weighted fine blocks (a gather, written once;
// docs/journal/2026-11-27-forming-coarse-grids.md).
//
// The cycle smooths with one forward block Gauss-Seidel sweep before the coarse correction and
// one backward sweep after it, and solves the coarsest level (at most 16 nodes) by a dense
// Cholesky factorisation. The preconditioner B is symmetric (restriction is P^T, the two sweeps
// are each other's adjoints in the A inner product) and BA's eigenvalues lie in (0, 1] (up to
// round-off: the sweeps' diagonal blocks are the inverses of the symmetric parts of A's
// diagonal blocks' inverses, symmetric_block_matrix.hpp): with G
// the forward sweep's error propagation, I - BA = G* (I - P B_c P^T A) G, and by induction over
// the grids B_c A_c has its eigenvalues in (0, 1] (at the coarsest B_c A_c = I), so
// I - P B_c P^T A is A-positive semidefinite and I - BA too; BA's eigenvalues are positive
// because Gauss-Seidel on SPD A is an A-norm contraction (|G e|_A < |e|_A), and the coarse
// correction never grows the A-norm. Tested against a dense reference cycle
// (tests/integrators/linear/test_grid_multigrid.cpp).
//
// Why bilinear: for a second-order operator, multigrid needs the orders of interpolation and
// restriction to add up to more than 2 (Trottenberg, Oosterlee and Schuller 2001, "Multigrid",
// the rule m_P + m_R > 2m; bilinear P and its transpose are of order 2 each). The piecewise-
// constant aggregation this replaced (order 1 each) fails that rule and weakened with every
// grid (docs/journal/2026-11-25-geometric-multigrid.md). On Poisson-like matrices the bilinear
// cycle's convergence does not depend on the number of grids (condition number 1.96 to 1.99 on
// 3 and 4 grids); on the hanging sheet, whose coefficients vary strongly, CG's iterations
// still grow with the grid (docs/performance/implicit-step.md).
#include <Eigen/Cholesky>
#include <vector>

#include "integrators/linear/symmetric_block_matrix.hpp"

namespace drape::detail {

/// One multigrid V-cycle as a symmetric positive definite preconditioner.
class GridMultigrid {
 public:
  /// Builds the levels for `fine`, whose row i is node i of a rows x cols grid (row-major).
  void build(const SymmetricBlockMatrix& fine, int rows, int cols);
  /// Forms the coarse operators from `fine`'s current values and factorises the coarsest.
  /// `fine` must have its diagonal inverted (SymmetricBlockMatrix::finish_row).
  void update(const SymmetricBlockMatrix& fine);
  /// out = B r, B the cycle started from zero.
  void apply(const SymmetricBlockMatrix& fine, const Eigen::VectorXd& r, Eigen::VectorXd& out);
  /// Number of grids, the fine one included.
  int levels() const { return static_cast<int>(m_levels.size()) + 1; }

 private:
  /// One term of a coarse block of A_c = P^T A P: weight * fine block `fine` (the weights are
  /// products of 1, 1/2 and 1/4, exact in float).
  struct GalerkinTerm {
    int fine;
    float weight;
  };
  /// A grid coarser than the one before it.
  struct Level {
    SymmetricBlockMatrix matrix;
    // P's rows: finer node i interpolates from parent[k] with weight[k],
    // k in [parent_start[i], parent_start[i + 1]).
    std::vector<int> parent_start, parent;
    std::vector<double> weight;
    // P's columns: coarse node c takes child[k] with child_weight[k],
    // k in [child_start[c], child_start[c + 1]), children ascending.
    std::vector<int> child_start, child;
    std::vector<double> child_weight;
    // Stored coarse block k sums galerkin[galerkin_start[k]] to
    // galerkin[galerkin_start[k + 1] - 1].
    std::vector<GalerkinTerm> galerkin;
    std::vector<int> galerkin_start;
    Eigen::VectorXd b, x, finer_residual;
  };

  void cycle(const SymmetricBlockMatrix& a, std::size_t next, const Eigen::VectorXd& b,
             Eigen::VectorXd& x);

  std::vector<Level> m_levels;
  Eigen::LLT<Eigen::MatrixXd> m_coarsest;
};

}  // namespace drape::detail
