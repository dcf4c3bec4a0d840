#include "integrators/newton/block_sparse_matrix.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <stdexcept>

namespace drape::detail {

namespace {

// The Gauss-Seidel sweeps request the blocks of the row `rows_ahead` rows on. Their rows wait on
// the row before (its x), so the processor cannot run ahead to the next rows' loads as in the
// product, and the forward sweep reads each row in two parts (L, then U a few rows later), a
// pattern the hardware's stream prefetcher does not follow. Once the blocks outgrew the cache
// (10.6 MB of double blocks at 128 x 128) each row then waited on memory: a multigrid cycle cost
// 4 to 5 times as much a row at 128 x 128 as at 64 x 64, and 1.5 to 2 times with these requests
// (docs/performance.md, "Prefetching the sweeps"; since "Single-precision sweeps" the sweeps
// read 5.3 MB there and a cycle costs the same a row at both sizes). Eight rows are about 3 KB
// of float blocks in flight; 2 to 24 rows measured alike with double blocks.
constexpr int rows_ahead = 8;
constexpr int cache_line = 64;

// Inlined by force: GCC finds a function that only prefetches free of side effects and drops
// its calls (it did here, unannounced, with a plain function).
[[gnu::always_inline]] inline void prefetch_row(const BlockSparseMatrix& a,
                                                 const Eigen::Matrix3f* blocks, int row) {
  if (row < 0 || row >= a.rows()) return;
  const char* first = reinterpret_cast<const char*>(blocks + a.row_start(row));
  const int bytes =
      (a.row_start(row + 1) - a.row_start(row)) * static_cast<int>(sizeof(Eigen::Matrix3f));
  for (int offset = 0; offset < bytes; offset += cache_line) __builtin_prefetch(first + offset);
}

}  // namespace

void BlockSparseMatrix::set_pattern(const std::vector<std::vector<int>>& neighbours) {
  const std::size_t n = neighbours.size();
  m_row_start.assign(n + 1, 0);
  m_upper_start.assign(n, 0);
  m_upper_reach = 0;
  m_column.clear();
  for (std::size_t i = 0; i < n; ++i) {
    m_column.push_back(static_cast<int>(i));
    std::vector<int> row = neighbours[i];
    // Ascending columns keep the vector reads of a row close together and split it into the
    // blocks left (L) and right (U) of the diagonal.
    std::sort(row.begin(), row.end());
    const auto upper = std::upper_bound(row.begin(), row.end(), static_cast<int>(i));
    m_upper_start[i] = static_cast<int>(m_column.size()) + static_cast<int>(upper - row.begin());
    if (!row.empty()) m_upper_reach = std::max(m_upper_reach, row.back() - static_cast<int>(i));
    m_column.insert(m_column.end(), row.begin(), row.end());
    m_row_start[i + 1] = static_cast<int>(m_column.size());
  }
  m_blocks.assign(m_column.size(), Mat3::Zero());
  m_diagonal_inverse.assign(n, Mat3::Identity());
  m_sweep_blocks.assign(m_column.size(), Eigen::Matrix3f::Identity());
  m_transpose.assign(m_column.size(), -1);
  m_symmetric_pattern = true;
  for (int i = 0; i < rows(); ++i)
    for (int k = row_start(i); k < row_start(i + 1); ++k) {
      m_transpose[static_cast<std::size_t>(k)] = find(column(k), i);
      m_symmetric_pattern = m_symmetric_pattern && m_transpose[static_cast<std::size_t>(k)] >= 0;
    }
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

void BlockSparseMatrix::finish_row(int i, bool sweeps) {
  const auto diagonal = static_cast<std::size_t>(row_start(i));
  Mat3& inverse = m_diagonal_inverse[static_cast<std::size_t>(i)];
  inverse = m_blocks[diagonal].inverse();
  if (!sweeps) return;
  if (!m_symmetric_pattern)
    throw std::logic_error("BlockSparseMatrix: the sweeps need a symmetric pattern");
  m_sweep_blocks[diagonal] = (0.5 * (inverse + inverse.transpose())).cast<float>();
  for (int k = m_upper_start[static_cast<std::size_t>(i)]; k < row_start(i + 1); ++k) {
    const Eigen::Matrix3f upper = m_blocks[static_cast<std::size_t>(k)].cast<float>();
    m_sweep_blocks[static_cast<std::size_t>(k)] = upper;
    m_sweep_blocks[static_cast<std::size_t>(m_transpose[static_cast<std::size_t>(k)])] =
        upper.transpose();
  }
}

void BlockSparseMatrix::finish_rows(bool sweeps) {
  for (int i = 0; i < rows(); ++i) finish_row(i, sweeps);
}

void BlockSparseMatrix::precondition_jacobi(const Eigen::VectorXd& r, Eigen::VectorXd& out) const {
  out.resize(r.size());
  for (int i = 0; i < rows(); ++i)
    particle(out, i).noalias() = m_diagonal_inverse[static_cast<std::size_t>(i)] * particle(r, i);
}

void BlockSparseMatrix::backward_sweep(const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
  const Eigen::Matrix3f* blocks = m_sweep_blocks.data();
  for (int i = rows() - 1; i >= 0; --i) {
    prefetch_row(*this, blocks, i - rows_ahead);
    Vec3 sum = particle(b, i);
    for (int k = row_start(i) + 1; k < row_start(i + 1); ++k)
      sum.noalias() -= blocks[k].cast<double>() * particle(x, column(k));
    particle(x, i).noalias() = blocks[row_start(i)].cast<double>() * sum;
  }
}

void BlockSparseMatrix::forward_sweep_from_zero(const Eigen::VectorXd& b, Eigen::VectorXd& x,
                                                Eigen::VectorXd& residual) const {
  x.resize(b.size());
  residual.resize(b.size());
  const Eigen::Matrix3f* blocks = m_sweep_blocks.data();
  // Row r of b - A x needs x up to row r + m_upper_reach: it is formed that many rows behind
  // the sweep, while row r's blocks are still in cache, instead of in a second pass.
  for (int i = 0; i < rows() + m_upper_reach; ++i) {
    if (i < rows()) {
      prefetch_row(*this, blocks, i + rows_ahead);
      Vec3 sum = particle(b, i);
      for (int k = row_start(i) + 1; k < m_upper_start[static_cast<std::size_t>(i)]; ++k)
        sum.noalias() -= blocks[k].cast<double>() * particle(x, column(k));
      particle(x, i).noalias() = blocks[row_start(i)].cast<double>() * sum;
    }
    const int r = i - m_upper_reach;
    if (r < 0) continue;
    // Row r's diagonal and left blocks cancel b_r by construction of x_r.
    Vec3 sum = Vec3::Zero();
    for (int k = m_upper_start[static_cast<std::size_t>(r)]; k < row_start(r + 1); ++k)
      sum.noalias() -= blocks[k].cast<double>() * particle(x, column(k));
    particle(residual, r) = sum;
  }
}

}  // namespace drape::detail
