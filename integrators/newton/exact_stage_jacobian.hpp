#pragma once
// The exact Jacobian of an implicit stage's velocity equation, factorised: Newton's local,
// quadratically convergent direction for LineSearchNewton (docs/integrators/line-search-newton.md,
// "Stages as minimisation").
//
// The stage residual g(v) = M (v - a_v) - gamma F(a_x + gamma v, v) (incremental_potential.hpp)
// has the Jacobian A = M - gamma D - gamma^2 K with the exact K, including the compressed
// springs' negative transverse stiffness and the spring damping's dependence on positions (the
// direction u turns with x): A is neither symmetric nor definite. The definite S that the line
// search needs to descend drops both, and there the iteration converges only linearly (rates
// 0.6-0.9 on the swinging sheet at 1/30 s; at 100x stiffness and 1/30 s the missing damping term
// made it cycle). A is factorised by sparse LU on the free particles (fixed rows: M I):
// SuiteSparse's UMFPACK (multifrontal, dense kernels in BLAS), 1.7x faster than Eigen's SparseLU on
// the 64 x 64 sheet's SDIRK2 step with OpenBLAS under it (docs/performance/sdirk-step.md).
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>
#include <Eigen/UmfPackSupport>
#include <functional>
#include <vector>

#include "core/model/cloth_system.hpp"

namespace drape {

/// Factorises the exact stage Jacobian A, optionally shifted by a multiple of M, and solves
/// (A + shift M) d = -g.
///
/// A is written in place into a matrix whose pattern is the spring graph's 3x3 blocks (full
/// blocks, explicit zeros kept), built once per fixed set: a Newton iteration then streams the
/// flat Jacobian blocks into the values (no triplets, no sparse temporaries), and UMFPACK's
/// symbolic analysis is redone only when the fixed set changes (an entry that happens to be
/// zero, as on an axis-aligned sheet, does not change the pattern).
class ExactStageJacobian {
 public:
  ExactStageJacobian(const ClothSystem& system, ForceSplit split);

  /// Applies an approximate inverse of A (zero on fixed particles): out = P r.
  using Preconditioner = std::function<void(const Eigen::VectorXd& r, Eigen::VectorXd& out)>;

  /// Forms A + shift M at (x, v) for `gamma`, for factorize() or krylov_direction(). A
  /// positive `shift` is the Levenberg-Marquardt shift of LineSearchNewton's local phase.
  void form(ConstVecRef x, ConstVecRef v, double gamma, double shift = 0.0);
  /// Factorises the formed matrix; false when it is singular.
  bool factorize();
  /// form(), then factorize().
  bool factorize(ConstVecRef x, ConstVecRef v, double gamma, double shift = 0.0);
  /// d = -(A + shift M)^-1 g (3N, zero on fixed particles) from the factorisation.
  void newton_direction(const Eigen::VectorXd& g, Eigen::VectorXd& d);
  /// d ~ -(A + shift M)^-1 g of the formed matrix by BiCGSTAB (van der Vorst 1992, SIAM J. Sci.
  /// Stat. Comput. 13(2); Eigen's, from d = 0) right-preconditioned by `preconditioner`: true
  /// when |A d + g| <= tolerance |g| within `max_iterations` (d is the last iterate otherwise).
  /// Adds the iterations taken to `iterations`.
  bool krylov_direction(const Eigen::VectorXd& g, Eigen::VectorXd& d,
                        const Preconditioner& preconditioner, double tolerance,
                        int max_iterations, long& iterations);

 private:
  /// Where a 3x3 block's three columns start in m_a's values (its rows are contiguous in
  /// each column); offset[0] < 0 for a block outside the pattern (a fixed particle's coupling).
  struct BlockSlot {
    int offset[3];
  };
  /// Builds m_a's pattern and the slots for the current fixed set.
  void build_pattern();
  BlockSlot slot_of(int row, int col) const;
  /// Adds `scale` times `block` to the block at `slot` (nothing outside the pattern).
  void add_block(const BlockSlot& slot, double scale, const Mat3& block);

  const ClothSystem& m_system;
  ForceSplit m_split;
  JacobianBlocks m_blocks;
  Eigen::SparseMatrix<double> m_a;
  std::vector<unsigned char> m_fixed;  // the fixed set m_a's pattern was built for
  std::vector<BlockSlot> m_diagonal;   // one per particle
  std::vector<BlockSlot> m_spring;     // four per spring: (i, i), (i, j), (j, i), (j, j)
  bool m_analysed = false;
  Eigen::UmfPackLU<Eigen::SparseMatrix<double>> m_lu;
  /// Eigen's preconditioner concept around a Preconditioner.
  struct KrylovPreconditioner {
    const Preconditioner* apply = nullptr;
    template <class Matrix>
    KrylovPreconditioner& analyzePattern(const Matrix&) { return *this; }
    template <class Matrix>
    KrylovPreconditioner& factorize(const Matrix&) { return *this; }
    template <class Matrix>
    KrylovPreconditioner& compute(const Matrix&) { return *this; }
    Eigen::ComputationInfo info() const { return Eigen::Success; }
    template <class Vector>
    Eigen::VectorXd solve(const Vector& r) const {
      Eigen::VectorXd out;
      (*apply)(r, out);
      return out;
    }
  };
  Eigen::BiCGSTAB<Eigen::SparseMatrix<double>, KrylovPreconditioner> m_krylov;
  Eigen::VectorXd m_rhs;  // -g: UmfPackLU solves a stored vector, not an expression
};

}  // namespace drape
