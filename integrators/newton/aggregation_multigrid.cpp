#include "integrators/newton/aggregation_multigrid.hpp"

#include <algorithm>
#include <stdexcept>

namespace drape::detail {

namespace {

// The coarsest grid is solved densely: 16 nodes are a 48 x 48 Cholesky factorisation, far
// cheaper than a fine-grid sweep.
constexpr int coarsest_nodes = 16;
// Over-correction (Vanek, Mandel and Brezina's "scaled" aggregation): a piecewise-constant
// prolongation undershoots smooth errors, so the coarse correction is stretched. CG iterations
// a step on the 64x64 benchmark for 1, 1.25, 1.5, 1.75, 2: 11.4, 10.0, 9.1, 9.4, 9.8.
constexpr double over_correction = 1.5;

Eigen::MatrixXd dense(const BlockSparseMatrix& a) {
  const Eigen::Index n3 = 3 * static_cast<Eigen::Index>(a.rows());
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(n3, n3);
  for (int i = 0; i < a.rows(); ++i)
    for (int k = a.row_start(i); k < a.row_start(i + 1); ++k)
      out.block<3, 3>(3 * i, 3 * a.column(k)) = a.blocks()[static_cast<std::size_t>(k)];
  return out;
}

}  // namespace

void AggregationMultigrid::build(const BlockSparseMatrix& fine, int rows, int cols) {
  m_levels.clear();
  const BlockSparseMatrix* finer = &fine;
  // Levels are held by value in a vector that grows: reserve so `finer` stays valid.
  int levels = 0;
  for (int r = rows, c = cols; r * c > coarsest_nodes; r = (r + 1) / 2, c = (c + 1) / 2) ++levels;
  m_levels.reserve(static_cast<std::size_t>(levels));
  while (rows * cols > coarsest_nodes) {
    const int coarse_cols = (cols + 1) / 2;
    Level& level = m_levels.emplace_back();
    level.aggregate.resize(static_cast<std::size_t>(rows * cols));
    for (int i = 0; i < rows * cols; ++i)
      level.aggregate[static_cast<std::size_t>(i)] = (i / cols) / 2 * coarse_cols + (i % cols) / 2;
    rows = (rows + 1) / 2;
    cols = coarse_cols;
    std::vector<std::vector<int>> neighbours(static_cast<std::size_t>(rows * cols));
    for (int i = 0; i < finer->rows(); ++i)
      for (int k = finer->row_start(i); k < finer->row_start(i + 1); ++k) {
        const int a = level.aggregate[static_cast<std::size_t>(i)];
        const int b = level.aggregate[static_cast<std::size_t>(finer->column(k))];
        auto& list = neighbours[static_cast<std::size_t>(a)];
        if (a != b && std::find(list.begin(), list.end(), b) == list.end()) list.push_back(b);
      }
    level.matrix.set_pattern(neighbours);
    level.entry.resize(finer->blocks().size());
    for (int i = 0; i < finer->rows(); ++i)
      for (int k = finer->row_start(i); k < finer->row_start(i + 1); ++k)
        level.entry[static_cast<std::size_t>(k)] =
            level.matrix.find(level.aggregate[static_cast<std::size_t>(i)],
                              level.aggregate[static_cast<std::size_t>(finer->column(k))]);
    finer = &level.matrix;
  }
}

void AggregationMultigrid::update(const BlockSparseMatrix& fine) {
  const BlockSparseMatrix* finer = &fine;
  for (Level& level : m_levels) {
    std::vector<Mat3>& coarse = level.matrix.blocks();
    std::fill(coarse.begin(), coarse.end(), Mat3::Zero());
    const std::vector<Mat3>& blocks = finer->blocks();
    for (std::size_t k = 0; k < blocks.size(); ++k)
      coarse[static_cast<std::size_t>(level.entry[k])] += blocks[k];
    level.matrix.invert_diagonal();
    finer = &level.matrix;
  }
  m_coarsest.compute(dense(*finer));
  if (m_coarsest.info() != Eigen::Success)
    throw std::logic_error("AggregationMultigrid: coarsest operator not positive definite");
}

void AggregationMultigrid::apply(const BlockSparseMatrix& fine, const Eigen::VectorXd& r,
                                 Eigen::VectorXd& out) {
  cycle(fine, 0, r, out);
}

void AggregationMultigrid::cycle(const BlockSparseMatrix& a, std::size_t next,
                                 const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  if (next == m_levels.size()) {
    x = m_coarsest.solve(b);
    return;
  }
  Level& coarse = m_levels[next];
  auto aggregate = [&](Eigen::Index i) { return coarse.aggregate[static_cast<std::size_t>(i)]; };
  a.forward_sweep_from_zero(b, x, coarse.finer_residual);
  // Restriction P^T sums each aggregate's residuals; prolongation P copies its correction back.
  coarse.b.setZero(3 * static_cast<Eigen::Index>(coarse.matrix.rows()));
  for (Eigen::Index i = 0; i < a.rows(); ++i)
    particle(coarse.b, aggregate(i)) += particle(coarse.finer_residual, i);
  cycle(coarse.matrix, next + 1, coarse.b, coarse.x);
  // Below the finest grid the coarse equation gets a second cycle on what the first left
  // (B2 = 2B - B A B, still symmetric positive definite for a convergent B): unsmoothed
  // aggregation's V-cycle weakens with every level, and these grids cost a quarter of the
  // finest one or less. CG iterations a step of the swinging sheet of bench_implicit_steps.cpp,
  // V-cycle: 13.4 at 64 x 64, 22.5 at 128 x 128; with the second cycle 10.7 and 16.8.
  if (next > 0) {
    coarse.matrix.multiply(coarse.x, coarse.remainder);
    coarse.remainder = coarse.b - coarse.remainder;
    cycle(coarse.matrix, next + 1, coarse.remainder, coarse.correction);
    coarse.x += coarse.correction;
  }
  for (Eigen::Index i = 0; i < a.rows(); ++i)
    particle(x, i) += over_correction * particle(coarse.x, aggregate(i));
  a.backward_sweep(b, x);
}

}  // namespace drape::detail
