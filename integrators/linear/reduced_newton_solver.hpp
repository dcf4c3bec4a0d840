#pragma once
// Newton's linear system of an implicit step of the cloth ODE, solved on the 3N velocities.
//
// With y = [x; v] and J = [0 I; M^-1 K  M^-1 D] on the free particles (K = dF/dx, D = dF/dv;
// a fixed particle's rows of J are zero because its right-hand side is prescribed), the system
// (I - gamma J) z = r reduces exactly to
//     S z_v = M r_v + gamma K r_x + gamma D r_v|fixed,   S = M - gamma D - gamma^2 K,
// on the free particles, then z_x = r_x + gamma z_v; a fixed particle keeps z = r. S uses the
// definite Jacobian (forces.hpp), so it is symmetric positive definite: conjugate gradients or
// a sparse Cholesky factorisation solve it (Baraff and Witkin 1998, section 5).
//
// S has the spring graph's 3x3 block sparsity, which never changes: a spring e = (i, j) with
// Jacobian blocks K_e, D_e couples i and j through -C_e, C_e = gamma D_e + gamma^2 K_e, and adds
// C_e to both diagonal blocks. CG keeps S's diagonal and upper blocks by block rows, each
// symmetric block packed (detail::SymmetricBlockMatrix), and preconditions with its block
// diagonal or a multigrid cycle on the cloth grid; the factorisation fills a compressed matrix
// whose pattern and symbolic analysis are built once.
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "core/model/cloth_system.hpp"
#include "integrators/linear/grid_multigrid.hpp"
#include "integrators/linear/symmetric_block_matrix.hpp"

namespace drape {

/// How the reduced system S is solved.
enum class ReducedSolve {
  conjugate_gradients,  ///< `pcg-reduced`: block-Jacobi preconditioned CG on S
  multigrid_cg,         ///< `pcg-multigrid`: CG on S preconditioned by a multigrid cycle
  sparse_ldlt,          ///< `sparse-direct`: Eigen's SimplicialLDLT factorisation of S
};

/// Where conjugate gradients start.
enum class CgStart {
  zero,  ///< z_v = 0 (a preconditioner: every right-hand side is unrelated to the last)
  /// The best combination of the last two `projected` solves' z_v (implicit Euler: the last
  /// two steps' dv): the Galerkin projection of S z_v = b onto their span, which minimises the
  /// error's S-norm over it, so the start is never worse than 0 or than the last dv alone in
  /// that norm (Fischer 1998, "Projection techniques for iterative solution of Ax = b with
  /// successive right-hand sides", Comput. Methods Appl. Mech. Engrg. 163;
  /// docs/journal/2026-11-27-cg-start-last-two-steps.md, "Starting CG from the last two steps").
  projected,
};

/// The method `integrator.linear_solver` names, or nothing for an unknown name.
std::optional<ReducedSolve> reduced_solve_named(const std::string& name);
/// Every accepted `integrator.linear_solver` name, comma separated (for error messages).
std::string reduced_solve_names();

/// Solves (I - gamma J) z = r for the cloth ODE through the reduced 3N system S.
class ReducedNewtonSolver {
 public:
  /// `split` selects the forces whose Jacobian J holds (all, or the springs for IMEX).
  ReducedNewtonSolver(const ClothSystem& system, ReducedSolve method, ForceSplit split,
                      double tolerance, int max_iterations);

  /// Evaluates the definite K and D blocks at (x, v) and forms S for `gamma`.
  void update(ConstVecRef x, ConstVecRef v, double gamma);
  /// Forms S for a new gamma from the last K and D.
  void set_gamma(double gamma);
  ReducedSolve method() const { return m_method; }
  /// False until update() runs, and again after invalidate().
  bool has_jacobian() const { return m_has_jacobian; }
  /// Forgets K and D (the constraints changed): the next setup must call update().
  void invalidate() { m_has_jacobian = false; }
  /// z = (I - gamma J)^-1 r for 6N vectors; false when CG stopped before its tolerance (z is
  /// then its last iterate). CG stops at the relative residual `tolerance`, or at the one given
  /// to the constructor when it is 0 (an inexact Newton's forcing term, line_search_newton.hpp).
  bool solve(ConstVecRef r, VecRef z, CgStart start = CgStart::zero, double tolerance = 0.0);
  /// out = P r, CG's preconditioner of the last S (zero on fixed particles).
  void precondition(const Eigen::VectorXd& r, Eigen::VectorXd& out);
  /// CG's relative residual given to the constructor.
  double tolerance() const { return m_tolerance; }
  /// CG iterations over all solves so far (0 for the direct solve).
  long iterations() const { return m_iterations; }

 private:
  /// Where a 3x3 block of S lives in m_s: entry (a, b) at values[base + b * stride + a].
  struct BlockSlot {
    Eigen::Index base = 0, stride = 0;
  };
  /// Where a stored block of m_matrix goes in m_s: at (i, j) and its mirror (j, i), whose
  /// stride is 0 for a diagonal block.
  struct BlockSlots {
    BlockSlot at, mirror;
  };

  /// S's stored blocks from the last K, D and gamma into m_matrix, row by row (the diagonal
  /// first, then the columns right of it ascending), then finish_row(i). S_ii = M - gamma D_ii -
  /// gamma^2 K_ii + sum of C_e over the springs at i, or M on a fixed particle; S_ij = -sum of C_e
  /// over the springs on (i, j) when both ends are free, 0 otherwise (C_e = gamma D_e + gamma^2
  /// K_e). Each block is written once, gathered from the spring blocks it sums, so S streams out
  /// in memory order (docs/journal/2026-11-27-assembling-s.md).
  template <class FinishRow>
  void assemble_blocks(FinishRow finish_row);
  /// Sets m_matrix's pattern and the spring lists of its blocks; returns each particle's spring
  /// neighbours.
  std::vector<std::vector<int>> build_gather();
  void form_system();
  void build_pattern();
  /// Copies m_matrix's blocks and their mirrors into m_s.
  void assemble_matrix();
  /// out = K r_x + D r_v|fixed (r_v on the fixed particles, 0 elsewhere), with the unclamped
  /// columns of fixed particles (rows not zeroed).
  void jacobian_times(ConstVecRef r_x, ConstVecRef r_v, Eigen::VectorXd& out) const;
  bool solve_reduced(const Eigen::VectorXd& b, Eigen::VectorXd& z_v, CgStart start,
                     double tolerance);
  /// z_v and m_residual = b - S z_v for CgStart::projected, from m_history.
  void start_projected(const Eigen::VectorXd& b, Eigen::VectorXd& z_v);
  /// CG on S z_v = b from z_v, whose residual is m_residual; false at max_iterations.
  bool conjugate_gradients(double b_norm, Eigen::VectorXd& z_v, double tolerance);

  const ClothSystem& m_system;
  ReducedSolve m_method;
  ForceSplit m_split;
  double m_tolerance;
  int m_max_iterations;
  double m_gamma = 0.0;
  bool m_has_jacobian = false;
  long m_iterations = 0;
  JacobianBlocks m_jacobian;
  // S by block rows (detail::SymmetricBlockMatrix; its pattern depends on the springs alone,
  // not on the fixed set) and, for each stored block k, the springs it sums:
  // block_springs[block_spring_start[k]] to block_springs[block_spring_start[k + 1] - 1] (a
  // diagonal block: the springs at i; an off-diagonal one: those on the pair).
  detail::SymmetricBlockMatrix m_matrix;
  std::vector<int> m_block_spring_start, m_block_springs;
  // pcg-multigrid only: the multigrid levels.
  detail::GridMultigrid m_multigrid;
  // sparse-direct only: S in a pattern built once (from m_matrix's blocks), where each stored
  // block k lives, the symbolic analysis.
  Eigen::SparseMatrix<double> m_s;
  std::vector<BlockSlots> m_block_slots;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> m_ldlt;
  Eigen::VectorXd m_b, m_z_v, m_residual, m_direction, m_preconditioned, m_product;
  // CgStart::projected: the last two such solves' z_v (newest first; empty until solved) and
  // their products by the current S.
  std::array<Eigen::VectorXd, 2> m_history, m_history_products;
};

}  // namespace drape
