#include "integrators/newton/block_sparse_matrix.hpp"

#include <Eigen/Dense>
#include <algorithm>

namespace drape::detail {

namespace {

// The Gauss-Seidel sweeps request the blocks of the row `rows_ahead` rows on. Their rows wait on
// the row before (its x), so the processor cannot run ahead to the next rows' loads as in the
// product, and the forward sweep's two passes read a part of each row (L, then U), a pattern
// the hardware's stream prefetcher does not follow. Once the blocks outgrow the cache (10.6 MB
// at 128 x 128) each row then waited on memory: a multigrid cycle cost 4 to 5 times as much a
// row at 128 x 128 as at 64 x 64, and 1.5 to 2 times with these requests (docs/performance.md,
// "Prefetching the sweeps"). Eight rows are about 5 KB in flight; 2 to 24 measured alike.
constexpr int rows_ahead = 8;
constexpr int cache_line = 64;

// Inlined by force: GCC finds a function that only prefetches free of side effects and drops
// its calls (it did here, unannounced, with a plain function).
[[gnu::always_inline]] inline void prefetch_row(const BlockSparseMatrix& a, int row) {
  if (row < 0 || row >= a.rows()) return;
  const char* first = reinterpret_cast<const char*>(a.blocks().data() + a.row_start(row));
  const int bytes = (a.row_start(row + 1) - a.row_start(row)) * static_cast<int>(sizeof(Mat3));
  for (int offset = 0; offset < bytes; offset += cache_line) __builtin_prefetch(first + offset);
}

}  // namespace

void BlockSparseMatrix::set_pattern(const std::vector<std::vector<int>>& neighbours) {
  const std::size_t n = neighbours.size();
  m_row_start.assign(n + 1, 0);
  m_upper_start.assign(n, 0);
  m_column.clear();
  for (std::size_t i = 0; i < n; ++i) {
    m_column.push_back(static_cast<int>(i));
    std::vector<int> row = neighbours[i];
    // Ascending columns keep the vector reads of a row close together and split it into the
    // blocks left (L) and right (U) of the diagonal.
    std::sort(row.begin(), row.end());
    const auto upper = std::upper_bound(row.begin(), row.end(), static_cast<int>(i));
    m_upper_start[i] = static_cast<int>(m_column.size()) + static_cast<int>(upper - row.begin());
    m_column.insert(m_column.end(), row.begin(), row.end());
    m_row_start[i + 1] = static_cast<int>(m_column.size());
  }
  m_blocks.assign(m_column.size(), Mat3::Zero());
  m_diagonal_inverse.assign(n, Mat3::Identity());
}

int BlockSparseMatrix::find(int i, int j) const {
  for (int k = row_start(i); k < row_start(i + 1); ++k)
    if (column(k) == j) return k;
  return -1;
}

void BlockSparseMatrix::multiply(const Eigen::VectorXd& p, Eigen::VectorXd& out) const {
  out.resize(p.size());
  for (int i = 0; i < rows(); ++i) {
    const int start = row_start(i), end = row_start(i + 1);
    Vec3 sum = m_blocks[static_cast<std::size_t>(start)] * particle(p, i);
    for (int k = start + 1; k < end; ++k)
      sum.noalias() += m_blocks[static_cast<std::size_t>(k)] * particle(p, column(k));
    particle(out, i) = sum;
  }
}

void BlockSparseMatrix::invert_diagonal() {
  for (int i = 0; i < rows(); ++i)
    m_diagonal_inverse[static_cast<std::size_t>(i)] =
        m_blocks[static_cast<std::size_t>(row_start(i))].inverse();
}

void BlockSparseMatrix::precondition_jacobi(const Eigen::VectorXd& r, Eigen::VectorXd& out) const {
  out.resize(r.size());
  for (int i = 0; i < rows(); ++i)
    particle(out, i).noalias() = m_diagonal_inverse[static_cast<std::size_t>(i)] * particle(r, i);
}

void BlockSparseMatrix::backward_sweep(const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
  for (int i = rows() - 1; i >= 0; --i) {
    prefetch_row(*this, i - rows_ahead);
    Vec3 sum = particle(b, i);
    for (int k = row_start(i) + 1; k < row_start(i + 1); ++k)
      sum.noalias() -= m_blocks[static_cast<std::size_t>(k)] * particle(x, column(k));
    particle(x, i).noalias() = m_diagonal_inverse[static_cast<std::size_t>(i)] * sum;
  }
}

void BlockSparseMatrix::forward_sweep_from_zero(const Eigen::VectorXd& b, Eigen::VectorXd& x,
                                                Eigen::VectorXd& residual) const {
  x.resize(b.size());
  residual.resize(b.size());
  for (int i = 0; i < rows(); ++i) {
    prefetch_row(*this, i + rows_ahead);
    Vec3 sum = particle(b, i);
    for (int k = row_start(i) + 1; k < m_upper_start[static_cast<std::size_t>(i)]; ++k)
      sum.noalias() -= m_blocks[static_cast<std::size_t>(k)] * particle(x, column(k));
    particle(x, i).noalias() = m_diagonal_inverse[static_cast<std::size_t>(i)] * sum;
  }
  // Row i of b - A x: its diagonal and left blocks cancel b_i by construction of x_i.
  for (int i = 0; i < rows(); ++i) {
    prefetch_row(*this, i + rows_ahead);
    Vec3 sum = Vec3::Zero();
    for (int k = m_upper_start[static_cast<std::size_t>(i)]; k < row_start(i + 1); ++k)
      sum.noalias() -= m_blocks[static_cast<std::size_t>(k)] * particle(x, column(k));
    particle(residual, i) = sum;
  }
}

}  // namespace drape::detail
