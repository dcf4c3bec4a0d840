#pragma once
// The exact Jacobian of an implicit stage's velocity equation, factorised: Newton's local,
// quadratically convergent direction for LineSearchNewton (docs/integrators.md, "Stages as
// minimisation").
//
// The stage residual g(v) = M (v - a_v) - gamma F(a_x + gamma v, v) (incremental_potential.hpp)
// has the Jacobian A = M - gamma D - gamma^2 K with the exact K, including the compressed
// springs' negative transverse stiffness and the spring damping's dependence on positions (the
// direction u turns with x): A is neither symmetric nor definite. The definite S that the line
// search needs to descend drops both, and there the iteration converges only linearly (rates
// 0.6-0.9 on the swinging sheet at 1/30 s; at 100x stiffness and 1/30 s the missing damping term
// made it cycle). A is factorised by sparse LU on the free particles (fixed rows: M I): SuiteSparse's
// UMFPACK (multifrontal, dense kernels in BLAS), 1.7x faster than Eigen's SparseLU on the 64 x 64
// sheet's SDIRK2 step with OpenBLAS under it (docs/performance.md, "Implicit steps at 1/30 s").
#include <Eigen/SparseCore>
#include <Eigen/UmfPackSupport>
#include <vector>

#include "core/model/cloth_system.hpp"

namespace drape {

/// Factorises the exact stage Jacobian A, optionally shifted by a multiple of M, and solves
/// (A + shift M) d = -g.
class ExactStageJacobian {
 public:
  ExactStageJacobian(const ClothSystem& system, ForceSplit split);

  /// Forms and factorises A + shift M at (x, v) for `gamma`; false when it is singular. A
  /// positive `shift` is the Levenberg-Marquardt shift of LineSearchNewton's local phase.
  bool factorize(ConstVecRef x, ConstVecRef v, double gamma, double shift = 0.0);
  /// d = -(A + shift M)^-1 g (3N, zero on fixed particles).
  void newton_direction(const Eigen::VectorXd& g, Eigen::VectorXd& d);

 private:
  /// True when m_a has the pattern of the last symbolic analysis.
  bool same_pattern() const;

  const ClothSystem& m_system;
  ForceSplit m_split;
  Eigen::SparseMatrix<double> m_dfdx, m_dfdv, m_a;
  Eigen::UmfPackLU<Eigen::SparseMatrix<double>> m_lu;
  std::vector<int> m_outer, m_inner;  // the analysed pattern of m_a
  Eigen::VectorXd m_rhs;  // -g: UmfPackLU solves a stored vector, not an expression
};

}  // namespace drape
