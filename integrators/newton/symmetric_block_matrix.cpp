#include "integrators/newton/symmetric_block_matrix.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <stdexcept>

namespace drape::detail {

namespace {

// The Gauss-Seidel sweeps request the blocks of the row `rows_ahead` rows on. Their rows wait on
// the row before (its x), so the processor cannot run ahead to the next rows' loads as in the
// product, and each sweep reads a row's blocks twice (once where it leads, again up to
// m_upper_reach rows later, then from the cache), a pattern the hardware's stream prefetcher
// does not follow. Once the blocks outgrew the cache each row then waited on memory
// (docs/journal/2026-11-26-prefetching-sweeps.md). Eight rows are about 2 KB of packed blocks
// in flight; 2 to 24 rows measured alike with full double blocks.
constexpr int rows_ahead = 8;
constexpr int cache_line = 64;

// Inlined by force: GCC finds a function that only prefetches free of side effects and drops
// its calls (it did here, unannounced, with a plain function).
[[gnu::always_inline]] inline void prefetch_row(const SymmetricBlockMatrix& a, int row) {
  if (row < 0 || row >= a.rows()) return;
  const char* first = reinterpret_cast<const char*>(a.blocks().data() + a.row_start(row));
  const int bytes =
      (a.row_start(row + 1) - a.row_start(row)) * static_cast<int>(sizeof(PackedBlock));
  for (int offset = 0; offset < bytes; offset += cache_line) __builtin_prefetch(first + offset);
}

}  // namespace

void SymmetricBlockMatrix::set_pattern(const std::vector<std::vector<int>>& neighbours) {
  const std::size_t n = neighbours.size();
  // Each pair once, in the row of its smaller end.
  std::vector<std::vector<int>> upper(n);
  for (std::size_t i = 0; i < n; ++i)
    for (const int j : neighbours[i]) {
      if (j < 0 || static_cast<std::size_t>(j) >= n)
        throw std::logic_error("SymmetricBlockMatrix: a neighbour outside the matrix");
      const auto low = static_cast<std::size_t>(std::min(static_cast<int>(i), j));
      const int high = std::max(static_cast<int>(i), j);
      if (static_cast<int>(low) != high) upper[low].push_back(high);
    }
  m_row_start.assign(n + 1, 0);
  m_upper_reach = 0;
  m_column.clear();
  for (std::size_t i = 0; i < n; ++i) {
    std::vector<int>& row = upper[i];
    // Ascending columns keep a row's vector reads close together.
    std::sort(row.begin(), row.end());
    row.erase(std::unique(row.begin(), row.end()), row.end());
    m_column.push_back(static_cast<int>(i));
    if (!row.empty()) m_upper_reach = std::max(m_upper_reach, row.back() - static_cast<int>(i));
    m_column.insert(m_column.end(), row.begin(), row.end());
    m_row_start[i + 1] = static_cast<int>(m_column.size());
  }
  m_blocks.assign(m_column.size(), PackedBlock::Zero());
  m_diagonal_inverse.assign(n, pack(Mat3::Identity()));
}

int SymmetricBlockMatrix::find(int i, int j) const {
  const int low = std::min(i, j), high = std::max(i, j);
  for (int k = row_start(low); k < row_start(low + 1); ++k)
    if (column(k) == high) return k;
  return -1;
}

void SymmetricBlockMatrix::multiply(const Eigen::VectorXd& p, Eigen::VectorXd& out) const {
  // Row i gathers its stored blocks' products and scatters each block's transpose (itself) to
  // the rows right of it, which have not been reached yet and are still in the cache.
  out.setZero(p.size());
  for (int i = 0; i < rows(); ++i) {
    const int start = row_start(i), end = row_start(i + 1);
    const Vec3 p_i = particle(p, i);
    Vec3 sum = times(m_blocks[static_cast<std::size_t>(start)], p_i);
    for (int k = start + 1; k < end; ++k) {
      const PackedBlock& block = m_blocks[static_cast<std::size_t>(k)];
      sum.noalias() += times(block, Vec3(particle(p, column(k))));
      particle(out, column(k)) += times(block, p_i);
    }
    particle(out, i) += sum;
  }
}

void SymmetricBlockMatrix::finish_row(int i) {
  m_diagonal_inverse[static_cast<std::size_t>(i)] =
      pack(unpack(m_blocks[static_cast<std::size_t>(row_start(i))]).inverse());
}

void SymmetricBlockMatrix::finish_rows() {
  for (int i = 0; i < rows(); ++i) finish_row(i);
}

void SymmetricBlockMatrix::precondition_jacobi(const Eigen::VectorXd& r,
                                               Eigen::VectorXd& out) const {
  out.resize(r.size());
  for (int i = 0; i < rows(); ++i)
    particle(out, i) = times(m_diagonal_inverse[static_cast<std::size_t>(i)], Vec3(particle(r, i)));
}

void SymmetricBlockMatrix::backward_sweep(const Eigen::VectorXd& b, Eigen::VectorXd& x,
                                          Eigen::VectorXd& scratch) const {
  // Row i needs L_i x_old = sum over the rows j < i coupled to it of U_ji x_j, x_j not yet
  // updated: row j scatters U_ji x_j to `scratch` m_upper_reach rows before the sweep reaches
  // i, while every x_j it reads is still old and every row it writes is still to come.
  scratch.setZero(b.size());
  const PackedBlock* blocks = m_blocks.data();
  for (int i = rows() - 1 + m_upper_reach; i >= 0; --i) {
    const int j = i - m_upper_reach;
    if (j >= 0 && j < rows()) {
      prefetch_row(*this, j - rows_ahead);
      const Vec3 x_j = particle(x, j);
      for (int k = row_start(j) + 1; k < row_start(j + 1); ++k)
        particle(scratch, column(k)) += times(blocks[k], x_j);
    }
    if (i >= rows()) continue;
    Vec3 sum = particle(b, i) - particle(scratch, i);
    for (int k = row_start(i) + 1; k < row_start(i + 1); ++k)
      sum.noalias() -= times(blocks[k], Vec3(particle(x, column(k))));
    particle(x, i) = times(m_diagonal_inverse[static_cast<std::size_t>(i)], sum);
  }
}

void SymmetricBlockMatrix::forward_sweep_from_zero(const Eigen::VectorXd& b, Eigen::VectorXd& x,
                                                   Eigen::VectorXd& residual) const {
  // x starts as b; row i, when reached, holds b_i - L_i x and becomes x_i, then scatters its
  // blocks' U_ij x_i (L_ji x_i) to the rows right of it. Row r of b - A x = -U x needs x up to
  // row r + m_upper_reach: it is formed that many rows behind the sweep, while row r's blocks
  // are still in cache, instead of in a second pass.
  x = b;
  residual.resize(b.size());
  const PackedBlock* blocks = m_blocks.data();
  for (int i = 0; i < rows() + m_upper_reach; ++i) {
    if (i < rows()) {
      prefetch_row(*this, i + rows_ahead);
      const Vec3 x_i = times(m_diagonal_inverse[static_cast<std::size_t>(i)], Vec3(particle(x, i)));
      particle(x, i) = x_i;
      for (int k = row_start(i) + 1; k < row_start(i + 1); ++k)
        particle(x, column(k)) -= times(blocks[k], x_i);
    }
    const int r = i - m_upper_reach;
    if (r < 0) continue;
    Vec3 sum = Vec3::Zero();
    for (int k = row_start(r) + 1; k < row_start(r + 1); ++k)
      sum.noalias() -= times(blocks[k], Vec3(particle(x, column(k))));
    particle(residual, r) = sum;
  }
}

}  // namespace drape::detail
