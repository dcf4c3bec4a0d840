#include "integrators/linear/reduced_newton_solver.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/parallel/fixed_block_sum.hpp"

namespace drape {

std::optional<ReducedSolve> reduced_solve_named(const std::string& name) {
  if (name == "pcg-reduced") return ReducedSolve::conjugate_gradients;
  if (name == "pcg-multigrid") return ReducedSolve::multigrid_cg;
  if (name == "sparse-direct") return ReducedSolve::sparse_ldlt;
  return std::nullopt;
}

std::string reduced_solve_names() { return "pcg-reduced, pcg-multigrid, sparse-direct"; }

namespace {

// Each particle's spring neighbours, ascending, without duplicates (two springs may join the
// same pair) and without the particle itself: S's off-diagonal block pattern.
std::vector<std::vector<int>> spring_neighbours(const SpringList& springs, int n) {
  std::vector<std::vector<int>> rows(static_cast<std::size_t>(n));
  for (Eigen::Index e = 0; e < springs.size(); ++e) {
    rows[static_cast<std::size_t>(springs.second[e])].push_back(springs.first[e]);
    rows[static_cast<std::size_t>(springs.first[e])].push_back(springs.second[e]);
  }
  for (auto& list : rows) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  return rows;
}

}  // namespace

ReducedNewtonSolver::ReducedNewtonSolver(const ClothSystem& system, ReducedSolve method,
                                         ForceSplit split, double tolerance, int max_iterations)
    : m_system(system),
      m_method(method),
      m_split(split),
      m_tolerance(tolerance),
      m_max_iterations(max_iterations) {}

void ReducedNewtonSolver::update(ConstVecRef x, ConstVecRef v, double gamma) {
  // The definite Jacobian: every block symmetric (the damping's non-symmetric position
  // derivative left out), as S's packed storage takes it (symmetric_block_matrix.hpp).
  m_system.force_jacobian_blocks(x, v, true, m_split, m_jacobian);
  m_has_jacobian = true;
  set_gamma(gamma);
}

void ReducedNewtonSolver::set_gamma(double gamma) {
  m_gamma = gamma;
  form_system();
}

template <class FinishRow>
void ReducedNewtonSolver::assemble_blocks(FinishRow finish_row) {
  const auto& fixed = m_system.constraints().mask();
  const double mass = m_system.particle_mass();
  const double g = m_gamma, g2 = m_gamma * m_gamma;
  std::vector<detail::PackedBlock>& blocks = m_matrix.blocks();
  // K's pair pattern [-J J; J -J] puts +C_e on both diagonal blocks of S and -C_e on (i, j) and
  // (j, i), one stored block (symmetric_block_matrix.hpp): each block sums its springs.
  const auto coupling = [&](int k) {
    detail::PackedBlock sum = detail::PackedBlock::Zero();
    for (int t = m_block_spring_start[static_cast<std::size_t>(k)];
         t < m_block_spring_start[static_cast<std::size_t>(k) + 1]; ++t) {
      const auto e = static_cast<std::size_t>(m_block_springs[static_cast<std::size_t>(t)]);
      sum.noalias() += detail::pack(g * m_jacobian.spring_v[e] + g2 * m_jacobian.spring_x[e]);
    }
    return sum;
  };
  const auto assemble_row = [&](int i) {
    const auto row = static_cast<std::size_t>(i);
    const int start = m_matrix.row_start(i), end = m_matrix.row_start(i + 1);
    if (fixed[row]) {
      // A fixed particle's row and column are dropped: its diagonal stays M and it couples to
      // nobody.
      blocks[static_cast<std::size_t>(start)] = detail::pack(mass * Mat3::Identity());
      for (int k = start + 1; k < end; ++k) blocks[static_cast<std::size_t>(k)].setZero();
    } else {
      blocks[static_cast<std::size_t>(start)] =
          detail::pack(mass * Mat3::Identity() - g * m_jacobian.particle_v[row] -
                       g2 * m_jacobian.particle_x[row]) +
          coupling(start);
      for (int k = start + 1; k < end; ++k) {
        detail::PackedBlock& block = blocks[static_cast<std::size_t>(k)];
        if (fixed[static_cast<std::size_t>(m_matrix.column(k))])
          block.setZero();
        else
          block = -coupling(k);
      }
    }
    finish_row(i);
  };
  // Each row writes only its own blocks and diagonal inverse: rows split among threads.
  parallel_for(m_matrix.rows(), threaded_particles_from,
               [&](std::ptrdiff_t first, std::ptrdiff_t last) {
                 for (auto i = static_cast<int>(first); i < last; ++i) assemble_row(i);
               });
}

std::vector<std::vector<int>> ReducedNewtonSolver::build_gather() {
  // The pattern depends on the springs alone, so it serves every later step, whatever the fixed
  // set (fixed particles' couplings are written as zeros).
  const SpringList& springs = m_system.cloth().springs;
  std::vector<std::vector<int>> neighbours =
      spring_neighbours(springs, m_system.num_particles());
  m_matrix.set_pattern(neighbours);
  // Each spring joins its two diagonal blocks and the block of its pair; the lists are filled
  // in spring order (counted, then placed).
  const auto for_each_term = [&](auto&& term) {
    for (Eigen::Index e = 0; e < springs.size(); ++e) {
      const int i = springs.first[e], j = springs.second[e];
      for (const int k : {m_matrix.find(i, i), m_matrix.find(j, j), m_matrix.find(i, j)})
        term(static_cast<std::size_t>(k), static_cast<int>(e));
    }
  };
  std::vector<int> count(m_matrix.blocks().size() + 1, 0);
  for_each_term([&](std::size_t k, int) { ++count[k + 1]; });
  for (std::size_t k = 1; k < count.size(); ++k) count[k] += count[k - 1];
  m_block_spring_start = count;
  m_block_springs.resize(static_cast<std::size_t>(count.back()));
  for_each_term([&](std::size_t k, int e) {
    m_block_springs[static_cast<std::size_t>(count[k]++)] = e;
  });
  return neighbours;
}

void ReducedNewtonSolver::form_system() {
  if (m_method == ReducedSolve::sparse_ldlt) {
    if (m_s.size() == 0) build_pattern();
    assemble_blocks([](int) {});
    assemble_matrix();
    m_ldlt.factorize(m_s);
    return;
  }
  if (m_matrix.rows() == 0) {
    build_gather();
    if (m_method == ReducedSolve::multigrid_cg) {
      const ClothParams& grid = m_system.cloth().params;
      m_multigrid.build(m_matrix, grid.rows, grid.cols);
    }
  }
  // Each row finished while in cache: its diagonal inverted (block Jacobi, the sweeps). Each
  // diagonal block is symmetric positive definite (a principal block of S).
  assemble_blocks([&](int i) { m_matrix.finish_row(i); });
  if (m_method == ReducedSolve::multigrid_cg) m_multigrid.update(m_matrix);
}

void ReducedNewtonSolver::precondition(const Eigen::VectorXd& r, Eigen::VectorXd& out) {
  if (m_method == ReducedSolve::conjugate_gradients) {
    m_matrix.precondition_jacobi(r, out);
    return;
  }
  // The coarse grids interpolate fixed particles' values together with free ones'; their rows
  // of S are decoupled (M I), so zeroing them keeps the preconditioner symmetric positive
  // definite on the free particles, where CG's iterates live.
  m_multigrid.apply(m_matrix, r, out);
  m_system.constraints().zero_fixed(out);
}

void ReducedNewtonSolver::build_pattern() {
  // Column block q holds the row blocks of q itself and of its spring neighbours, ascending;
  // its three columns share that row list. Like the row pattern, it and the fill-reducing
  // ordering serve every later step, whatever the fixed set.
  std::vector<std::vector<int>> rows = build_gather();
  const int n = m_system.num_particles();
  for (int q = 0; q < n; ++q) {
    auto& list = rows[static_cast<std::size_t>(q)];
    list.insert(std::upper_bound(list.begin(), list.end(), q), q);
  }
  std::vector<Eigen::Index> column_start(static_cast<std::size_t>(n) + 1, 0);
  for (std::size_t q = 0; q < rows.size(); ++q)
    column_start[q + 1] = column_start[q] + 9 * static_cast<Eigen::Index>(rows[q].size());
  const Eigen::Index n3 = 3 * static_cast<Eigen::Index>(n);
  m_s.resize(n3, n3);
  m_s.resizeNonZeros(column_start.back());
  auto* outer = m_s.outerIndexPtr();
  auto* inner = m_s.innerIndexPtr();
  for (std::size_t q = 0; q < rows.size(); ++q) {
    const auto stride = 3 * static_cast<Eigen::Index>(rows[q].size());
    for (Eigen::Index b = 0; b < 3; ++b) {
      const Eigen::Index start = column_start[q] + b * stride;
      outer[3 * q + static_cast<std::size_t>(b)] = static_cast<int>(start);
      for (std::size_t k = 0; k < rows[q].size(); ++k)
        for (int a = 0; a < 3; ++a)
          inner[start + 3 * static_cast<Eigen::Index>(k) + a] = 3 * rows[q][k] + a;
    }
  }
  outer[n3] = static_cast<int>(column_start.back());
  // Block (p, q): rows 3p.. of columns 3q.. (rank of p in column q's list). A stored block k
  // at (p, q), q >= p, fills (p, q) and its mirror (q, p) (one slot on the diagonal).
  const auto slot = [&](int p, int q) {
    const auto& list = rows[static_cast<std::size_t>(q)];
    const auto rank = std::lower_bound(list.begin(), list.end(), p) - list.begin();
    return BlockSlot{column_start[static_cast<std::size_t>(q)] + 3 * rank,
                     3 * static_cast<Eigen::Index>(list.size())};
  };
  m_block_slots.clear();
  for (int p = 0; p < n; ++p)
    for (int k = m_matrix.row_start(p); k < m_matrix.row_start(p + 1); ++k) {
      const int q = m_matrix.column(k);
      m_block_slots.push_back({slot(p, q), q == p ? BlockSlot{} : slot(q, p)});
    }
  m_s.coeffs().setZero();
  m_ldlt.analyzePattern(m_s);
}

void ReducedNewtonSolver::assemble_matrix() {
  // Every entry of the pattern is a stored block or its mirror: written once, nothing zeroed.
  double* values = m_s.valuePtr();
  const std::vector<detail::PackedBlock>& blocks = m_matrix.blocks();
  for (std::size_t k = 0; k < blocks.size(); ++k) {
    const Mat3 block = detail::unpack(blocks[k]);
    for (const BlockSlot& slot : {m_block_slots[k].at, m_block_slots[k].mirror}) {
      if (slot.stride == 0) continue;  // a diagonal block has no mirror
      for (Eigen::Index b = 0; b < 3; ++b)
        for (Eigen::Index a = 0; a < 3; ++a) values[slot.base + b * slot.stride + a] = block(a, b);
    }
  }
}

void ReducedNewtonSolver::jacobian_times(ConstVecRef r_x, ConstVecRef r_v,
                                         Eigen::VectorXd& out) const {
  // D's columns enter only at fixed particles (D r_v|fixed): D's blocks are read there alone,
  // half of the spring blocks this pass would otherwise stream.
  const SpringList& springs = m_system.cloth().springs;
  const auto& fixed = m_system.constraints().mask();
  out.resize(r_x.size());
  for (std::size_t i = 0; i < m_jacobian.particle_x.size(); ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    particle(out, k).noalias() = m_jacobian.particle_x[i] * particle(r_x, k);
    if (fixed[i]) particle(out, k).noalias() += m_jacobian.particle_v[i] * particle(r_v, k);
  }
  for (Eigen::Index e = 0; e < springs.size(); ++e) {
    const auto s = static_cast<std::size_t>(e);
    const int i = springs.first[e], j = springs.second[e];
    Vec3 df = m_jacobian.spring_x[s] * (particle(r_x, j) - particle(r_x, i));
    const bool fixed_i = fixed[static_cast<std::size_t>(i)] != 0;
    const bool fixed_j = fixed[static_cast<std::size_t>(j)] != 0;
    if (fixed_i || fixed_j) {
      const Vec3 w_i = fixed_i ? Vec3(particle(r_v, i)) : Vec3::Zero();
      const Vec3 w_j = fixed_j ? Vec3(particle(r_v, j)) : Vec3::Zero();
      df.noalias() += m_jacobian.spring_v[s] * (w_j - w_i);
    }
    particle(out, i) += df;
    particle(out, j) -= df;
  }
}

bool ReducedNewtonSolver::solve(ConstVecRef r, VecRef z, CgStart start, double tolerance) {
  const Eigen::Index n3 = r.size() / 2;
  const auto r_x = r.head(n3), r_v = r.tail(n3);
  const ConstraintSet& constraints = m_system.constraints();
  // b = M r_v + gamma (K r_x + D r_v|fixed): the fixed particles' known z enters through the
  // columns of K and D, whose fixed rows are dropped.
  jacobian_times(r_x, r_v, m_product);
  m_b = m_system.particle_mass() * r_v + m_gamma * m_product;
  constraints.zero_fixed(m_b);
  const bool converged =
      solve_reduced(m_b, m_z_v, start, tolerance > 0.0 ? tolerance : m_tolerance);
  z.tail(n3) = m_z_v;
  z.head(n3) = r_x + m_gamma * m_z_v;
  for (const int i : constraints.fixed_particles()) {
    particle(z.tail(n3), i) = particle(r_v, i);
    particle(z.head(n3), i) = particle(r_x, i);
  }
  return converged;
}

bool ReducedNewtonSolver::solve_reduced(const Eigen::VectorXd& b, Eigen::VectorXd& z_v,
                                        CgStart start, double tolerance) {
  if (m_method == ReducedSolve::sparse_ldlt) {
    z_v = m_ldlt.solve(b);
    return m_ldlt.info() == Eigen::Success;
  }
  // The iterates stay zero on fixed particles: b and the preconditioner are zero there.
  if (start == CgStart::projected) {
    start_projected(b, z_v);
  } else {
    z_v.setZero(b.size());
    m_residual = b;
  }
  const bool converged = conjugate_gradients(block_norm(b), z_v, tolerance);
  if (start == CgStart::projected) {
    std::swap(m_history[0], m_history[1]);
    m_history[0] = z_v;
  }
  return converged;
}

void ReducedNewtonSolver::start_projected(const Eigen::VectorXd& b, Eigen::VectorXd& z_v) {
  // z_v = U c with (U' S U) c = U' b, U the stored solves: the S-orthogonal projection of the
  // solution onto span U. The 2x2 system is solved on its eigenvalues above a relative cutoff,
  // so that parallel, zero or missing (empty) columns drop out instead of dividing by zero; the
  // cutoff 1e-10 stays above the Gram entries' rounding (about 3N machine epsilons relative,
  // 5e-12 at 128 x 128), below which the projection's guarantee would not hold.
  Eigen::Matrix2d gram = Eigen::Matrix2d::Zero();
  Eigen::Vector2d projected_b = Eigen::Vector2d::Zero();
  for (std::size_t a = 0; a < m_history.size(); ++a) {
    Eigen::VectorXd& u = m_history[a];
    if (u.size() != b.size()) u.setZero(b.size());
    m_system.constraints().zero_fixed(u);  // the fixed set may have changed since
    m_matrix.multiply(u, m_history_products[a]);
    projected_b(static_cast<Eigen::Index>(a)) = u.dot(b);
  }
  for (Eigen::Index a = 0; a < 2; ++a)
    for (Eigen::Index c = 0; c < 2; ++c)
      gram(a, c) = 0.5 * (m_history[static_cast<std::size_t>(a)].dot(
                              m_history_products[static_cast<std::size_t>(c)]) +
                          m_history[static_cast<std::size_t>(c)].dot(
                              m_history_products[static_cast<std::size_t>(a)]));
  if (!gram.allFinite() || !projected_b.allFinite()) {  // a diverged solve: forget it, start at 0
    for (Eigen::VectorXd& u : m_history) u.setZero(b.size());
    z_v.setZero(b.size());
    m_residual = b;
    return;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(gram);
  const double cutoff = 1e-10 * eigen.eigenvalues().cwiseAbs().maxCoeff();
  Eigen::Vector2d c = Eigen::Vector2d::Zero();
  for (Eigen::Index k = 0; k < 2; ++k)
    if (eigen.eigenvalues()(k) > cutoff)
      c += eigen.eigenvectors().col(k) *
           (eigen.eigenvectors().col(k).dot(projected_b) / eigen.eigenvalues()(k));
  z_v = c(0) * m_history[0] + c(1) * m_history[1];
  m_residual = b - c(0) * m_history_products[0] - c(1) * m_history_products[1];
}

bool ReducedNewtonSolver::conjugate_gradients(double b_norm, Eigen::VectorXd& z_v,
                                              double tolerance) {
  // Preconditioned conjugate gradients (Shewchuk 1994, B2) from z_v, m_residual = b - S z_v,
  // stopping at |b - S z| <= tolerance |b| (at once for b = 0, whose start is then 0). Every
  // dot product and norm is a fixed-block sum (core/parallel/fixed_block_sum.hpp) and each
  // iteration's updates of z and r share one pass with |r|: the same bits on any number of
  // threads.
  if (block_norm(m_residual) <= tolerance * b_norm) return true;
  precondition(m_residual, m_preconditioned);
  m_direction = m_preconditioned;
  double rho = block_dot(m_residual, m_preconditioned);
  for (int k = 0; k < m_max_iterations; ++k) {
    m_matrix.multiply(m_direction, m_product);
    const double alpha = rho / block_dot(m_direction, m_product);
    const double residual_norm = std::sqrt(fixed_block_sum(
        z_v.size(), entries_per_block, [&](std::ptrdiff_t begin, std::ptrdiff_t end) {
          const Eigen::Index n = end - begin;
          z_v.segment(begin, n) += alpha * m_direction.segment(begin, n);
          m_residual.segment(begin, n) -= alpha * m_product.segment(begin, n);
          return m_residual.segment(begin, n).squaredNorm();
        }));
    ++m_iterations;
    if (residual_norm <= tolerance * b_norm) return true;
    precondition(m_residual, m_preconditioned);
    const double rho_next = block_dot(m_residual, m_preconditioned);
    const double beta = rho_next / rho;
    parallel_for(z_v.size(), 3 * threaded_particles_from,
                 [&](std::ptrdiff_t begin, std::ptrdiff_t end) {
                   const Eigen::Index n = end - begin;
                   m_direction.segment(begin, n) =
                       m_preconditioned.segment(begin, n) + beta * m_direction.segment(begin, n);
                 });
    rho = rho_next;
  }
  return false;
}

}  // namespace drape
