#include "integrators/linear/grid_multigrid.hpp"

#include <algorithm>
#include <stdexcept>
#include <utility>

#include "core/parallel/parallel_for.hpp"

namespace drape::detail {

namespace {

// The coarsest grid is solved densely: 16 nodes are a 48 x 48 Cholesky factorisation, far
// cheaper than a fine-grid sweep.
constexpr int coarsest_nodes = 16;

/// Linear interpolation along one grid direction of n fine nodes: fine node r's coarse parents
/// and weights (coarse node r / 2 sits on fine node r for even r).
std::vector<std::pair<int, double>> parents_1d(int r, int n) {
  if (r % 2 == 0) return {{r / 2, 1.0}};
  if (r + 1 < n) return {{r / 2, 0.5}, {r / 2 + 1, 0.5}};
  return {{r / 2, 1.0}};  // past the last coarse node of an even-sized grid
}

Eigen::MatrixXd dense(const SymmetricBlockMatrix& a) {
  const Eigen::Index n3 = 3 * static_cast<Eigen::Index>(a.rows());
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(n3, n3);
  for (int i = 0; i < a.rows(); ++i)
    for (int k = a.row_start(i); k < a.row_start(i + 1); ++k) {
      const Mat3 block = unpack(a.blocks()[static_cast<std::size_t>(k)]);
      out.block<3, 3>(3 * i, 3 * a.column(k)) = block;
      out.block<3, 3>(3 * a.column(k), 3 * i) = block;
    }
  return out;
}

}  // namespace

void GridMultigrid::build(const SymmetricBlockMatrix& fine, int rows, int cols) {
  m_levels.clear();
  const SymmetricBlockMatrix* finer = &fine;
  // Levels are held by value in a vector that grows: reserve so `finer` stays valid.
  int levels = 0;
  for (int r = rows, c = cols; r * c > coarsest_nodes; r = (r + 1) / 2, c = (c + 1) / 2) ++levels;
  m_levels.reserve(static_cast<std::size_t>(levels));
  while (rows * cols > coarsest_nodes) {
    const int coarse_rows = (rows + 1) / 2, coarse_cols = (cols + 1) / 2;
    Level& level = m_levels.emplace_back();
    level.parent_start.assign(1, 0);
    for (int i = 0; i < rows * cols; ++i) {
      for (const auto& [pr, wr] : parents_1d(i / cols, rows))
        for (const auto& [pc, wc] : parents_1d(i % cols, cols)) {
          level.parent.push_back(pr * coarse_cols + pc);
          level.weight.push_back(wr * wc);
        }
      level.parent_start.push_back(static_cast<int>(level.parent.size()));
    }
    // Block (i, j) of A adds weight_iI weight_jJ A_ij to block (I, J) of P^T A P for every
    // parent I of i and J of j. A stored block k is both A_ij and A_ji (the same symmetric
    // matrix), so it is visited at both positions.
    auto for_each_term = [&](auto&& add) {
      const auto add_pair = [&](int k, int i, int j) {
        for (int p = level.parent_start[static_cast<std::size_t>(i)];
             p < level.parent_start[static_cast<std::size_t>(i) + 1]; ++p)
          for (int q = level.parent_start[static_cast<std::size_t>(j)];
               q < level.parent_start[static_cast<std::size_t>(j) + 1]; ++q)
            add(k, level.parent[static_cast<std::size_t>(p)],
                level.parent[static_cast<std::size_t>(q)],
                level.weight[static_cast<std::size_t>(p)] *
                    level.weight[static_cast<std::size_t>(q)]);
      };
      for (int i = 0; i < finer->rows(); ++i)
        for (int k = finer->row_start(i); k < finer->row_start(i + 1); ++k) {
          const int j = finer->column(k);
          add_pair(k, i, j);
          if (j != i) add_pair(k, j, i);
        }
    };
    std::vector<std::vector<int>> neighbours(static_cast<std::size_t>(coarse_rows * coarse_cols));
    for_each_term([&](int, int a, int b, double) {
      auto& list = neighbours[static_cast<std::size_t>(a)];
      if (a != b && std::find(list.begin(), list.end(), b) == list.end()) list.push_back(b);
    });
    level.matrix.set_pattern(neighbours);
    // The terms of each stored coarse block, the one at (a, b) with b >= a (the terms at
    // (b, a) are those same terms' transposes, the same matrices).
    std::vector<std::vector<GalerkinTerm>> terms(level.matrix.blocks().size());
    for_each_term([&](int k, int a, int b, double w) {
      if (b >= a)
        terms[static_cast<std::size_t>(level.matrix.find(a, b))].push_back(
            {k, static_cast<float>(w)});
    });
    level.galerkin_start.assign(1, 0);
    for (const auto& list : terms) {
      level.galerkin.insert(level.galerkin.end(), list.begin(), list.end());
      level.galerkin_start.push_back(static_cast<int>(level.galerkin.size()));
    }
    // P's columns (P^T's rows, for the restriction's gather): coarse node c's finer nodes
    // ascending, the order in which a scatter through P's rows would add them.
    level.child_start.assign(static_cast<std::size_t>(coarse_rows * coarse_cols) + 1, 0);
    for (const int c : level.parent) ++level.child_start[static_cast<std::size_t>(c) + 1];
    for (std::size_t c = 1; c < level.child_start.size(); ++c)
      level.child_start[c] += level.child_start[c - 1];
    level.child.resize(level.parent.size());
    level.child_weight.resize(level.parent.size());
    std::vector<int> next(level.child_start.begin(), level.child_start.end() - 1);
    for (int i = 0; i < rows * cols; ++i)
      for (int p = level.parent_start[static_cast<std::size_t>(i)];
           p < level.parent_start[static_cast<std::size_t>(i) + 1]; ++p) {
        const auto slot = static_cast<std::size_t>(
            next[static_cast<std::size_t>(level.parent[static_cast<std::size_t>(p)])]++);
        level.child[slot] = i;
        level.child_weight[slot] = level.weight[static_cast<std::size_t>(p)];
      }
    rows = coarse_rows;
    cols = coarse_cols;
    finer = &level.matrix;
  }
}

void GridMultigrid::update(const SymmetricBlockMatrix& fine) {
  const SymmetricBlockMatrix* finer = &fine;
  for (Level& level : m_levels) {
    const SymmetricBlockMatrix& a = level.matrix;
    std::vector<PackedBlock>& coarse = level.matrix.blocks();
    const std::vector<PackedBlock>& blocks = finer->blocks();
    // Each coarse row gathers its own blocks: rows split among threads.
    const auto form_row = [&](int i) {
      for (int k = a.row_start(i); k < a.row_start(i + 1); ++k) {
        PackedBlock sum = PackedBlock::Zero();
        for (int t = level.galerkin_start[static_cast<std::size_t>(k)];
             t < level.galerkin_start[static_cast<std::size_t>(k) + 1]; ++t) {
          const GalerkinTerm& term = level.galerkin[static_cast<std::size_t>(t)];
          sum.noalias() += static_cast<double>(term.weight) *
                           blocks[static_cast<std::size_t>(term.fine)];
        }
        coarse[static_cast<std::size_t>(k)] = sum;
      }
      level.matrix.finish_row(i);
    };
    parallel_for(a.rows(), threaded_particles_from, [&](std::ptrdiff_t first, std::ptrdiff_t last) {
      for (auto i = static_cast<int>(first); i < last; ++i) form_row(i);
    });
    finer = &level.matrix;
  }
  m_coarsest.compute(dense(*finer));
  if (m_coarsest.info() != Eigen::Success)
    throw std::logic_error("GridMultigrid: coarsest operator not positive definite");
}

void GridMultigrid::apply(const SymmetricBlockMatrix& fine, const Eigen::VectorXd& r,
                          Eigen::VectorXd& out) {
  cycle(fine, 0, r, out);
}

void GridMultigrid::cycle(const SymmetricBlockMatrix& a, std::size_t next, const Eigen::VectorXd& b,
                          Eigen::VectorXd& x) {
  if (next == m_levels.size()) {
    x = m_coarsest.solve(b);
    return;
  }
  Level& coarse = m_levels[next];
  a.forward_sweep_from_zero(b, x, coarse.finer_residual);
  // Restriction P^T r through P's columns, then prolongation x += P x_c through its rows: each
  // a gather per node, split among threads.
  coarse.b.resize(3 * static_cast<Eigen::Index>(coarse.matrix.rows()));
  parallel_for(coarse.matrix.rows(), threaded_particles_from,
               [&](std::ptrdiff_t first, std::ptrdiff_t last) {
                 for (std::ptrdiff_t c = first; c < last; ++c) {
                   Vec3 sum = Vec3::Zero();
                   for (int k = coarse.child_start[static_cast<std::size_t>(c)];
                        k < coarse.child_start[static_cast<std::size_t>(c) + 1]; ++k)
                     sum +=
                         coarse.child_weight[static_cast<std::size_t>(k)] *
                         particle(coarse.finer_residual, coarse.child[static_cast<std::size_t>(k)]);
                   particle(coarse.b, c) = sum;
                 }
               });
  cycle(coarse.matrix, next + 1, coarse.b, coarse.x);
  parallel_for(a.rows(), threaded_particles_from, [&](std::ptrdiff_t first, std::ptrdiff_t last) {
    for (std::ptrdiff_t i = first; i < last; ++i)
      for (int p = coarse.parent_start[static_cast<std::size_t>(i)];
           p < coarse.parent_start[static_cast<std::size_t>(i) + 1]; ++p)
        particle(x, i) += coarse.weight[static_cast<std::size_t>(p)] *
                          particle(coarse.x, coarse.parent[static_cast<std::size_t>(p)]);
  });
  a.backward_sweep(b, x, coarse.finer_residual);  // the residual is restricted: its storage free
}

}  // namespace drape::detail
