#include "integrators/newton/reduced_newton_solver.hpp"

#include <Eigen/Dense>
#include <algorithm>

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
std::vector<std::vector<int>> spring_neighbours(const SpringSet& springs, int n) {
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
  m_system.force_jacobian_blocks(x, v, true, m_split, m_jacobian);
  m_has_jacobian = true;
  set_gamma(gamma);
}

void ReducedNewtonSolver::set_gamma(double gamma) {
  m_gamma = gamma;
  form_system();
}

template <class SetDiagonal, class AddDiagonal, class SetCoupling>
void ReducedNewtonSolver::for_each_block(SetDiagonal set_diagonal, AddDiagonal add_diagonal,
                                         SetCoupling set_coupling) const {
  const SpringSet& springs = m_system.cloth().springs;
  const auto& fixed = m_system.constraints().mask();
  const double mass = m_system.particle_mass();
  const double g = m_gamma, g2 = m_gamma * m_gamma;
  // A fixed particle's row and column are dropped: its diagonal stays M and it couples to
  // nobody.
  for (std::size_t i = 0; i < m_jacobian.particle_x.size(); ++i)
    set_diagonal(i, fixed[i] ? Mat3(mass * Mat3::Identity())
                             : Mat3(mass * Mat3::Identity() - g * m_jacobian.particle_v[i] -
                                    g2 * m_jacobian.particle_x[i]));
  for (std::size_t e = 0; e < m_jacobian.spring_x.size(); ++e) {
    const auto i = static_cast<std::size_t>(springs.first[static_cast<Eigen::Index>(e)]);
    const auto j = static_cast<std::size_t>(springs.second[static_cast<Eigen::Index>(e)]);
    const Mat3 c = g * m_jacobian.spring_v[e] + g2 * m_jacobian.spring_x[e];
    // K's pair pattern [-J J; J -J] puts +C_e on both diagonal blocks of S and -C_e on (i, j)
    // and (j, i).
    if (!fixed[i]) add_diagonal(i, c);
    if (!fixed[j]) add_diagonal(j, c);
    set_coupling(e, fixed[i] || fixed[j] ? Mat3(Mat3::Zero()) : Mat3(-c));
  }
}

void ReducedNewtonSolver::form_system() {
  if (m_method == ReducedSolve::sparse_ldlt) {
    if (m_s.size() == 0) build_pattern();
    assemble_matrix();
    m_ldlt.factorize(m_s);
    return;
  }
  if (m_matrix.rows() == 0) build_block_rows();
  assemble_block_rows();
  // Each diagonal block is symmetric positive definite (a principal block of S).
  m_matrix.invert_diagonal();
  if (m_method == ReducedSolve::multigrid_cg) {
    m_matrix.prepare_sweeps();
    m_multigrid.update(m_matrix);
  }
}

void ReducedNewtonSolver::build_block_rows() {
  // Like the compressed pattern, the block rows depend on the springs alone: fixed particles'
  // couplings are stored as zeros.
  const SpringSet& springs = m_system.cloth().springs;
  m_matrix.set_pattern(spring_neighbours(springs, m_system.num_particles()));
  m_spring_blocks.resize(2 * static_cast<std::size_t>(springs.size()));
  m_first_on_pair.assign(static_cast<std::size_t>(springs.size()), 0);
  std::vector<char> taken(m_matrix.blocks().size(), 0);
  for (Eigen::Index e = 0; e < springs.size(); ++e) {
    const int i = springs.first[e], j = springs.second[e];
    const int ij = m_matrix.find(i, j);
    m_spring_blocks[2 * static_cast<std::size_t>(e)] = ij;
    m_spring_blocks[2 * static_cast<std::size_t>(e) + 1] = m_matrix.find(j, i);
    m_first_on_pair[static_cast<std::size_t>(e)] = !taken[static_cast<std::size_t>(ij)];
    // Both orientations: a later spring on (j, i) shares the pair's two blocks.
    taken[static_cast<std::size_t>(ij)] = 1;
    taken[static_cast<std::size_t>(m_matrix.transpose(ij))] = 1;
  }
  if (m_method == ReducedSolve::multigrid_cg) {
    const ClothParams& grid = m_system.cloth().params;
    m_multigrid.build(m_matrix, grid.rows, grid.cols);
  }
}

void ReducedNewtonSolver::assemble_block_rows() {
  // One pass that writes every block, none zeroed first: every off-diagonal block belongs to a
  // spring, and the first spring on a pair writes it, any other adds (two springs may join
  // the same pair). C_e is symmetric (the definite Jacobian has no damping position term), so
  // S_ij = S_ji = -C_e.
  std::vector<Mat3>& blocks = m_matrix.blocks();
  const auto diagonal = [&](std::size_t i) -> Mat3& {
    return blocks[static_cast<std::size_t>(m_matrix.row_start(static_cast<int>(i)))];
  };
  for_each_block([&](std::size_t i, const Mat3& d) { diagonal(i) = d; },
                 [&](std::size_t i, const Mat3& c) { diagonal(i) += c; },
                 [&](std::size_t e, const Mat3& s_ij) {
                   for (const int k : {m_spring_blocks[2 * e], m_spring_blocks[2 * e + 1]}) {
                     Mat3& block = blocks[static_cast<std::size_t>(k)];
                     if (m_first_on_pair[e])
                       block = s_ij;
                     else
                       block += s_ij;
                   }
                 });
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
  // its three columns share that row list. The pattern depends on the springs alone, so it and
  // the fill-reducing ordering serve every later step, whatever the fixed set.
  const SpringSet& springs = m_system.cloth().springs;
  const int n = m_system.num_particles();
  std::vector<std::vector<int>> rows = spring_neighbours(springs, n);
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
  auto slot = [&](int p, int q) {
    const auto& list = rows[static_cast<std::size_t>(q)];
    const auto rank = std::lower_bound(list.begin(), list.end(), p) - list.begin();
    return BlockSlot{column_start[static_cast<std::size_t>(q)] + 3 * rank,
                     3 * static_cast<Eigen::Index>(list.size())};
  };
  m_diagonal_slots.resize(static_cast<std::size_t>(n));
  for (int q = 0; q < n; ++q) m_diagonal_slots[static_cast<std::size_t>(q)] = slot(q, q);
  m_spring_slots.resize(2 * static_cast<std::size_t>(springs.size()));
  for (Eigen::Index e = 0; e < springs.size(); ++e) {
    m_spring_slots[2 * static_cast<std::size_t>(e)] = slot(springs.first[e], springs.second[e]);
    m_spring_slots[2 * static_cast<std::size_t>(e) + 1] = slot(springs.second[e], springs.first[e]);
  }
  m_s.coeffs().setZero();
  m_ldlt.analyzePattern(m_s);
}

void ReducedNewtonSolver::assemble_matrix() {
  double* values = m_s.valuePtr();
  // Accumulated, not written: the diagonal blocks sum every spring's C_e.
  std::fill(values, values + m_s.nonZeros(), 0.0);
  auto add = [&](const BlockSlot& slot, const Mat3& block) {
    for (Eigen::Index b = 0; b < 3; ++b)
      for (Eigen::Index a = 0; a < 3; ++a) values[slot.base + b * slot.stride + a] += block(a, b);
  };
  for_each_block([&](std::size_t i, const Mat3& d) { add(m_diagonal_slots[i], d); },
                 [&](std::size_t i, const Mat3& c) { add(m_diagonal_slots[i], c); },
                 [&](std::size_t e, const Mat3& s_ij) {
                   add(m_spring_slots[2 * e], s_ij);
                   add(m_spring_slots[2 * e + 1], s_ij.transpose());
                 });
}

void ReducedNewtonSolver::jacobian_times(ConstVecRef r_x, const Eigen::VectorXd& w,
                                         Eigen::VectorXd& out) const {
  const SpringSet& springs = m_system.cloth().springs;
  out.resize(r_x.size());
  for (std::size_t i = 0; i < m_jacobian.particle_x.size(); ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    particle(out, k).noalias() =
        m_jacobian.particle_x[i] * particle(r_x, k) + m_jacobian.particle_v[i] * particle(w, k);
  }
  for (Eigen::Index e = 0; e < springs.size(); ++e) {
    const auto s = static_cast<std::size_t>(e);
    const int i = springs.first[e], j = springs.second[e];
    const Vec3 df = m_jacobian.spring_x[s] * (particle(r_x, j) - particle(r_x, i)) +
                    m_jacobian.spring_v[s] * (particle(w, j) - particle(w, i));
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
  m_fixed_r_v.setZero(n3);
  for (const int i : constraints.fixed_particles()) particle(m_fixed_r_v, i) = particle(r_v, i);
  jacobian_times(r_x, m_fixed_r_v, m_product);
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
  const bool converged = conjugate_gradients(b.norm(), z_v, tolerance);
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
  // stopping at |b - S z| <= tolerance |b| (at once for b = 0, whose start is then 0).
  if (m_residual.norm() <= tolerance * b_norm) return true;
  precondition(m_residual, m_preconditioned);
  m_direction = m_preconditioned;
  double rho = m_residual.dot(m_preconditioned);
  for (int k = 0; k < m_max_iterations; ++k) {
    m_matrix.multiply(m_direction, m_product);
    const double alpha = rho / m_direction.dot(m_product);
    z_v += alpha * m_direction;
    m_residual -= alpha * m_product;
    ++m_iterations;
    if (m_residual.norm() <= tolerance * b_norm) return true;
    precondition(m_residual, m_preconditioned);
    const double rho_next = m_residual.dot(m_preconditioned);
    m_direction = m_preconditioned + (rho_next / rho) * m_direction;
    rho = rho_next;
  }
  return false;
}

}  // namespace drape
