#include "integrators/linear/symmetric_block_matrix.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <stdexcept>

#include "core/parallel/parallel_for.hpp"

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
  out.resize(p.size());
  parallel_for(rows(), threaded_particles_from, [&](std::ptrdiff_t begin, std::ptrdiff_t end) {
    multiply_rows(p, out, static_cast<int>(begin), static_cast<int>(end));
  });
}

void SymmetricBlockMatrix::multiply_rows(const Eigen::VectorXd& p, Eigen::VectorXd& out,
                                         int begin, int end) const {
  // Row i gathers its stored blocks' products and scatters each block's transpose (itself) to
  // the rows right of it, which have not been reached yet and are still in the cache. A row r
  // of out sums, in this order, the transposed blocks of the rows above it, ascending, then its
  // own row: rows [begin, end) first take those of the rows above `begin`, then run the loop,
  // scattering only inside [begin, end), so that every row's sum is the one-thread loop's
  // whatever the split.
  out.segment(3 * static_cast<Eigen::Index>(begin), 3 * static_cast<Eigen::Index>(end - begin))
      .setZero();
  add_from_above(p, out, begin, end, 1.0);
  for (int i = begin; i < end; ++i) {
    const int start = row_start(i), stop = row_start(i + 1);
    const Vec3 p_i = particle(p, i);
    Vec3 sum = times(m_blocks[static_cast<std::size_t>(start)], p_i);
    for (int k = start + 1; k < stop; ++k) {
      const PackedBlock& block = m_blocks[static_cast<std::size_t>(k)];
      sum.noalias() += times(block, Vec3(particle(p, column(k))));
      if (column(k) < end) particle(out, column(k)) += times(block, p_i);
    }
    particle(out, i) += sum;
  }
}

void SymmetricBlockMatrix::add_from_above(const Eigen::VectorXd& v, Eigen::VectorXd& out,
                                          int begin, int end, double sign) const {
  for (int j = std::max(0, begin - m_upper_reach); j < begin; ++j) {
    const Vec3 v_j = particle(v, j);
    for (int k = row_start(j) + 1; k < row_start(j + 1); ++k)
      if (column(k) >= begin && column(k) < end)
        particle(out, column(k)) += sign * times(m_blocks[static_cast<std::size_t>(k)], v_j);
  }
}

void SymmetricBlockMatrix::add_from_below(const Eigen::VectorXd& v, Eigen::VectorXd& out,
                                          int begin, int end, double sign) const {
  for (int r = std::max(begin, end - m_upper_reach); r < end; ++r)
    for (int k = row_start(r) + 1; k < row_start(r + 1); ++k)
      if (column(k) >= end)
        particle(out, r) += sign * times(m_blocks[static_cast<std::size_t>(k)],
                                         Vec3(particle(v, column(k))));
}

void SymmetricBlockMatrix::finish_row(int i) {
  m_diagonal_inverse[static_cast<std::size_t>(i)] =
      pack(unpack(m_blocks[static_cast<std::size_t>(row_start(i))]).inverse());
}

void SymmetricBlockMatrix::finish_rows() {
  parallel_for(rows(), threaded_particles_from, [&](std::ptrdiff_t begin, std::ptrdiff_t end) {
    for (auto i = static_cast<int>(begin); i < end; ++i) finish_row(i);
  });
}

void SymmetricBlockMatrix::precondition_jacobi(const Eigen::VectorXd& r,
                                               Eigen::VectorXd& out) const {
  out.resize(r.size());
  parallel_for(rows(), threaded_particles_from, [&](std::ptrdiff_t begin, std::ptrdiff_t end) {
    for (auto i = static_cast<int>(begin); i < end; ++i)
      particle(out, i) =
          times(m_diagonal_inverse[static_cast<std::size_t>(i)], Vec3(particle(r, i)));
  });
}

void SymmetricBlockMatrix::set_sweep_block_rows(int rows) {
  if (rows < 1) throw std::logic_error("SymmetricBlockMatrix: a sweep block of no rows");
  m_sweep_block_rows = rows;
}

int SymmetricBlockMatrix::sweep_blocks() const {
  return (rows() + m_sweep_block_rows - 1) / m_sweep_block_rows;
}

template <class Body>
void SymmetricBlockMatrix::for_each_sweep_block(Body&& body) const {
  parallel_for(sweep_blocks(), 2, [&](std::ptrdiff_t first, std::ptrdiff_t last) {
    for (auto block = static_cast<int>(first); block < last; ++block)
      body(block * m_sweep_block_rows, std::min(rows(), (block + 1) * m_sweep_block_rows));
  });
}

void SymmetricBlockMatrix::backward_sweep(const Eigen::VectorXd& b, Eigen::VectorXd& x,
                                          Eigen::VectorXd& scratch) const {
  // Row i needs L_i x_old = sum over the rows j < i coupled to it of U_ji x_j, x_j not yet
  // updated: row j scatters U_ji x_j to `scratch` m_upper_reach rows before the sweep reaches
  // i, while every x_j it reads is still old and every row it writes is still to come. Rows
  // coupled to another sweep block take that block's old x first, before any block moves.
  scratch.resize(b.size());
  const bool one_block = sweep_blocks() == 1;
  if (!one_block)
    for_each_sweep_block([&](int begin, int end) {
      scratch.segment(3 * static_cast<Eigen::Index>(begin),
                      3 * static_cast<Eigen::Index>(end - begin))
          .setZero();
      add_from_above(x, scratch, begin, end, 1.0);
      add_from_below(x, scratch, begin, end, 1.0);
    });
  for_each_sweep_block([&](int begin, int end) {
    if (one_block) scratch.setZero();
    backward_sweep_rows(b, x, scratch, begin, end);
  });
}

void SymmetricBlockMatrix::backward_sweep_rows(const Eigen::VectorXd& b, Eigen::VectorXd& x,
                                               Eigen::VectorXd& scratch, int begin,
                                               int end) const {
  const PackedBlock* blocks = m_blocks.data();
  for (int i = end - 1 + m_upper_reach; i >= begin; --i) {
    const int j = i - m_upper_reach;
    if (j >= begin && j < end) {
      prefetch_row(*this, j - rows_ahead);
      const Vec3 x_j = particle(x, j);
      for (int k = row_start(j) + 1; k < row_start(j + 1) && column(k) < end; ++k)
        particle(scratch, column(k)) += times(blocks[k], x_j);
    }
    if (i >= end) continue;
    Vec3 sum = particle(b, i) - particle(scratch, i);
    for (int k = row_start(i) + 1; k < row_start(i + 1) && column(k) < end; ++k)
      sum.noalias() -= times(blocks[k], Vec3(particle(x, column(k))));
    particle(x, i) = times(m_diagonal_inverse[static_cast<std::size_t>(i)], sum);
  }
}

void SymmetricBlockMatrix::forward_sweep_from_zero(const Eigen::VectorXd& b, Eigen::VectorXd& x,
                                                   Eigen::VectorXd& residual) const {
  // From x = 0 the other blocks' x are zero during the sweep, so each block sweeps alone; the
  // residual's couplings across blocks are added once every block's x is final.
  x.resize(b.size());
  residual.resize(b.size());
  for_each_sweep_block(
      [&](int begin, int end) { forward_sweep_rows(b, x, residual, begin, end); });
  if (sweep_blocks() > 1)
    for_each_sweep_block([&](int begin, int end) {
      add_from_above(x, residual, begin, end, -1.0);
      add_from_below(x, residual, begin, end, -1.0);
    });
}

void SymmetricBlockMatrix::forward_sweep_rows(const Eigen::VectorXd& b, Eigen::VectorXd& x,
                                              Eigen::VectorXd& residual, int begin,
                                              int end) const {
  // x starts as b; row i, when reached, holds b_i - L_i x and becomes x_i, then scatters its
  // blocks' U_ij x_i (L_ji x_i) to the rows right of it. Row r of b - A x = -U x needs x up to
  // row r + m_upper_reach: it is formed that many rows behind the sweep, while row r's blocks
  // are still in cache, instead of in a second pass.
  const Eigen::Index first = 3 * static_cast<Eigen::Index>(begin);
  const Eigen::Index count = 3 * static_cast<Eigen::Index>(end - begin);
  x.segment(first, count) = b.segment(first, count);
  const PackedBlock* blocks = m_blocks.data();
  for (int i = begin; i < end + m_upper_reach; ++i) {
    if (i < end) {
      prefetch_row(*this, i + rows_ahead);
      const Vec3 x_i = times(m_diagonal_inverse[static_cast<std::size_t>(i)], Vec3(particle(x, i)));
      particle(x, i) = x_i;
      for (int k = row_start(i) + 1; k < row_start(i + 1) && column(k) < end; ++k)
        particle(x, column(k)) -= times(blocks[k], x_i);
    }
    const int r = i - m_upper_reach;
    if (r < begin) continue;
    Vec3 sum = Vec3::Zero();
    for (int k = row_start(r) + 1; k < row_start(r + 1) && column(k) < end; ++k)
      sum.noalias() -= times(blocks[k], Vec3(particle(x, column(k))));
    particle(residual, r) = sum;
  }
}

}  // namespace drape::detail
