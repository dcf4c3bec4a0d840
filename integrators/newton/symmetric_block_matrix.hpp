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

  /// out = A p.
  void multiply(const Eigen::VectorXd& p, Eigen::VectorXd& out) const;
  /// Inverts row i's diagonal block (for precondition_jacobi() and the sweeps; it must be
  /// invertible, positive definite for an SPD matrix). Needs row i's diagonal block final.
  void finish_row(int i);
  /// finish_row() for every row.
  void finish_rows();
  /// out = D^-1 r, D the block diagonal (the symmetric part of each block's inverse).
  void precondition_jacobi(const Eigen::VectorXd& r, Eigen::VectorXd& out) const;
  /// One block Gauss-Seidel sweep on A x = b with rows descending:
  /// x = (D + U)^-1 (b - L x), L and U the blocks left and right of the diagonal, D^-1 the
  /// symmetric parts of the diagonal blocks' inverses. `scratch` is overwritten (L x, gathered
  /// as the sweep goes) and must not alias `b` or `x`.
  void backward_sweep(const Eigen::VectorXd& b, Eigen::VectorXd& x,
                      Eigen::VectorXd& scratch) const;
  /// The forward sweep (rows ascending) from x = 0, x = (D + L)^-1 b, and the residual it
  /// leaves, b - A x = -U x (A with the diagonal the sweeps see): together one pass
  /// over the blocks instead of a sweep and a product, each row's residual formed as soon as
  /// the x it reads is final. `residual` must not alias `b` or `x`.
  void forward_sweep_from_zero(const Eigen::VectorXd& b, Eigen::VectorXd& x,
                               Eigen::VectorXd& residual) const;

 private:
  std::vector<int> m_row_start{0}, m_column;  // row_start of an empty matrix: rows() = 0
  int m_upper_reach = 0;  // the largest column - row of a stored block
  std::vector<PackedBlock> m_blocks;
  std::vector<PackedBlock> m_diagonal_inverse;  // the symmetric part of each D_i^-1
};

}  // namespace drape::detail
