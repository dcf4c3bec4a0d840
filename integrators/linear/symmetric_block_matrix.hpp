#pragma once
// A symmetric matrix of symmetric 3x3 blocks, stored once: the reduced system S and the coarse
// levels of its multigrid preconditioner. Every block of S is symmetric (a spring's coupling
// C_e = gamma D_e + gamma^2 K_e is a combination of u u' and I, a diagonal block a sum of such
// and of the particle's own symmetric terms), and S itself is, so each row keeps its diagonal
// block and the blocks right of it only, each packed as its upper triangle (6 numbers, not 9):
// about 240 bytes a row of the cloth's 9-point pattern instead of the 648 of every block in full.
// The product and the Gauss-Seidel sweeps read each stored block once and apply it to both of
// its positions, (i, j) and (j, i), which is the same matrix; at 128 x 128 the blocks outgrow the
// cache and a CG iteration's cost is the bytes it streams
// (docs/journal/2026-11-28-s-stored-once.md).
//
// The Gauss-Seidel sweeps read the same blocks, in double, with the symmetric part of each
// diagonal block's inverse (so that the cycle is exactly symmetric, which CG needs). Until S was
// stored once they read a single-precision copy
// (docs/journal/2026-11-27-single-precision-sweeps.md, "Single-precision sweeps"); on the packed
// blocks the conversions cost more than the bytes the copy saved, and the copy was one more array
// to write a step ("S stored once").
//
// On threads (docs/performance/threads.md), with the same bits for any number of them: the
// product splits its rows among the threads, each row summing its terms in the one-thread
// order; the sweeps run over fixed blocks of 2048 rows, Gauss-Seidel within a block
// and Jacobi between blocks (each block reads the others' x from before the sweep): the
// "hybrid Gauss-Seidel" of Baker, Falgout, Kolev and Yang 2011 ("Multigrid smoothers for
// ultraparallel computing", SIAM J. Sci. Comput. 33(5)), here with blocks fixed by the matrix,
// not by the threads. The backward sweep is still the forward one's adjoint (its M is D + U
// within blocks, the transpose of the forward D + L), so the cycle stays symmetric; it stays an
// A-norm contraction while M + M' - A = D - C (C the couplings between blocks) is positive
// definite, which holds for S, whose couplings are the springs' -C_e with C_e positive
// semi-definite. A matrix of at most 2048 rows is one block: the sweeps of before.
//
// A row is finished (its diagonal inverted) by finish_row() as soon as its blocks hold their
// values, so that an assembly writing row by row does it while the row is in cache instead of in
// one more pass over the matrix (docs/journal/2026-11-27-assembling-s.md).
#include <vector>

#include "core/state/state.hpp"

namespace drape::detail {

/// A symmetric 3x3 block as its upper triangle: (xx, xy, xz, yy, yz, zz).
template <class Scalar>
using PackedSymmetric = Eigen::Matrix<Scalar, 6, 1>;
using PackedBlock = PackedSymmetric<double>;

/// The symmetric part (m + m') / 2 of m, packed (m itself when it is symmetric).
inline PackedBlock pack(const Mat3& m) {
  return PackedBlock(m(0, 0), 0.5 * (m(0, 1) + m(1, 0)), 0.5 * (m(0, 2) + m(2, 0)), m(1, 1),
                     0.5 * (m(1, 2) + m(2, 1)), m(2, 2));
}

/// The full block of a packed one.
template <class Scalar>
inline Mat3 unpack(const PackedSymmetric<Scalar>& p) {
  Mat3 m;
  m << p(0), p(1), p(2), p(1), p(3), p(4), p(2), p(4), p(5);
  return m;
}

/// The packed block times v, in double.
template <class Scalar>
inline Vec3 times(const PackedSymmetric<Scalar>& p, const Vec3& v) {
  const double a = p(0), b = p(1), c = p(2), d = p(3), e = p(4), f = p(5);
  return {a * v(0) + b * v(1) + c * v(2), b * v(0) + d * v(1) + e * v(2),
          c * v(0) + e * v(1) + f * v(2)};
}

/// A square symmetric matrix of symmetric 3x3 blocks with a fixed pattern that always holds
/// the diagonal.
class SymmetricBlockMatrix {
 public:
  /// Sets the pattern: `neighbours[i]` lists columns coupled to row i (a pair may be listed
  /// from either end or both, more than once; i itself is ignored; a column outside the matrix
  /// throws std::logic_error). Every block becomes zero.
  void set_pattern(const std::vector<std::vector<int>>& neighbours);
  /// Number of block rows.
  int rows() const { return static_cast<int>(m_row_start.size()) - 1; }
  /// Index in blocks() of the block at (i, j) and (j, i), or -1 when the pair is not coupled.
  int find(int i, int j) const;
  /// Row i stores blocks()[row_start(i)] (its diagonal) to blocks()[row_start(i + 1) - 1], the
  /// blocks right of the diagonal in ascending columns.
  int row_start(int i) const { return m_row_start[static_cast<std::size_t>(i)]; }
  int column(int k) const { return m_column[static_cast<std::size_t>(k)]; }
  std::vector<PackedBlock>& blocks() { return m_blocks; }
  const std::vector<PackedBlock>& blocks() const { return m_blocks; }

  /// out = A p, on threads for a cloth's worth of rows (core/parallel), the same bits for any
  /// number of them.
  void multiply(const Eigen::VectorXd& p, Eigen::VectorXd& out) const;
  /// Inverts row i's diagonal block (for precondition_jacobi() and the sweeps; it must be
  /// invertible, positive definite for an SPD matrix). Needs row i's diagonal block final.
  void finish_row(int i);
  /// finish_row() for every row.
  void finish_rows();
  /// out = D^-1 r, D the block diagonal (the symmetric part of each block's inverse).
  void precondition_jacobi(const Eigen::VectorXd& r, Eigen::VectorXd& out) const;
  /// Rows of a sweep block (at least 1; 2048 unless set): each block is swept on one thread.
  void set_sweep_block_rows(int rows);
  /// One block Gauss-Seidel sweep on A x = b with rows descending:
  /// x = (D + U)^-1 (b - L x), L and U the blocks left and right of the diagonal within a sweep
  /// block (those between sweep blocks act on the old x, with L), D^-1 the
  /// symmetric parts of the diagonal blocks' inverses. `scratch` is overwritten (L x, gathered
  /// as the sweep goes) and must not alias `b` or `x`.
  void backward_sweep(const Eigen::VectorXd& b, Eigen::VectorXd& x,
                      Eigen::VectorXd& scratch) const;
  /// The forward sweep (rows ascending) from x = 0, x = (D + L)^-1 b (L within sweep blocks),
  /// and the residual it leaves, b - A x = -(U + C) x (C the couplings between sweep blocks; A
  /// with the diagonal the sweeps see): together one pass
  /// over the blocks instead of a sweep and a product, each row's residual formed as soon as
  /// the x it reads is final. `residual` must not alias `b` or `x`.
  void forward_sweep_from_zero(const Eigen::VectorXd& b, Eigen::VectorXd& x,
                               Eigen::VectorXd& residual) const;

 private:
  /// Rows [begin, end) of out = A p (out's other rows untouched).
  void multiply_rows(const Eigen::VectorXd& p, Eigen::VectorXd& out, int begin, int end) const;
  /// out's rows [begin, end) += sign times the stored blocks of the rows above `begin` that
  /// reach them (their lower part), applied to v, rows ascending.
  void add_from_above(const Eigen::VectorXd& v, Eigen::VectorXd& out, int begin, int end,
                      double sign) const;
  /// out's rows [begin, end) += sign times their stored blocks reaching past `end`, applied
  /// to v.
  void add_from_below(const Eigen::VectorXd& v, Eigen::VectorXd& out, int begin, int end,
                      double sign) const;
  int sweep_blocks() const;
  /// body(begin, end) for every sweep block's rows, the blocks split among the threads.
  template <class Body>
  void for_each_sweep_block(Body&& body) const;
  /// The sweeps within rows [begin, end), coupling to no row outside.
  void backward_sweep_rows(const Eigen::VectorXd& b, Eigen::VectorXd& x,
                           Eigen::VectorXd& scratch, int begin, int end) const;
  void forward_sweep_rows(const Eigen::VectorXd& b, Eigen::VectorXd& x,
                          Eigen::VectorXd& residual, int begin, int end) const;

  // Rows a sweep block holds: by default as many as a loop needs to be worth threads
  // (threaded_particles_from, core/parallel).
  int m_sweep_block_rows = 2048;
  std::vector<int> m_row_start{0}, m_column;  // row_start of an empty matrix: rows() = 0
  int m_upper_reach = 0;  // the largest column - row of a stored block
  std::vector<PackedBlock> m_blocks;
  std::vector<PackedBlock> m_diagonal_inverse;  // the symmetric part of each D_i^-1
};

}  // namespace drape::detail
