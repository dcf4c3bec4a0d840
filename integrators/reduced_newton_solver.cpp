#include "integrators/reduced_newton_solver.hpp"

#include <Eigen/Dense>

namespace drape {

std::optional<ReducedSolve> reduced_solve_named(const std::string& name) {
  if (name == "pcg-reduced") return ReducedSolve::conjugate_gradients;
  if (name == "sparse-direct") return ReducedSolve::sparse_ldlt;
  return std::nullopt;
}

std::string reduced_solve_names() { return "pcg-reduced, sparse-direct"; }

ReducedNewtonSolver::ReducedNewtonSolver(const ClothSystem& system, ReducedSolve method,
                                         ForceSplit split, double tolerance, int max_iterations)
    : m_system(system),
      m_method(method),
      m_split(split),
      m_tolerance(tolerance),
      m_max_iterations(max_iterations) {}

void ReducedNewtonSolver::update(ConstVecRef x, ConstVecRef v, double gamma) {
  m_system.force_jacobians(x, v, true, m_dfdx, m_dfdv, m_split);
  m_has_jacobian = true;
  set_gamma(gamma);
}

void ReducedNewtonSolver::set_gamma(double gamma) {
  m_gamma = gamma;
  form_system();
}

void ReducedNewtonSolver::form_system() {
  const Eigen::Index n3 = m_dfdx.rows();
  Eigen::SparseMatrix<double> mass(n3, n3);
  mass.setIdentity();
  mass *= m_system.particle_mass();
  m_s = mass - m_gamma * m_dfdv - (m_gamma * m_gamma) * m_dfdx;
  // A fixed particle's rows of K and D are already zero; dropping its columns too leaves S
  // symmetric with M on its diagonal, decoupled from the free particles (its z_v is known).
  const auto& fixed = m_system.constraints().mask();
  m_s.prune([&](Eigen::Index row, Eigen::Index col, double) {
    return row == col || !fixed[static_cast<std::size_t>(col / 3)];
  });
  if (m_method == ReducedSolve::sparse_ldlt) {
    m_ldlt.compute(m_s);
    return;
  }
  const Eigen::Index n = n3 / 3;
  m_block_inverse.assign(static_cast<std::size_t>(n), Mat3::Zero());
  for (Eigen::Index col = 0; col < n3; ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator it(m_s, col); it; ++it)
      if (it.row() / 3 == col / 3) m_block_inverse[col / 3](it.row() % 3, col % 3) = it.value();
  // Each diagonal block is symmetric positive definite (a principal block of S).
  for (Mat3& block : m_block_inverse) block = block.ldlt().solve(Mat3::Identity());
}

bool ReducedNewtonSolver::solve(ConstVecRef r, VecRef z) {
  const Eigen::Index n3 = r.size() / 2;
  const auto r_x = r.head(n3), r_v = r.tail(n3);
  // b = M r_v + gamma (K r_x + D r_v|fixed): the fixed particles' known z enters through the
  // columns of K and D, whose fixed rows are zero.
  m_fixed_r_v = r_v;
  for (Eigen::Index i = 0; i < n3 / 3; ++i)
    if (!m_system.constraints().is_fixed(static_cast<int>(i))) particle(m_fixed_r_v, i).setZero();
  m_b = m_system.particle_mass() * r_v + m_gamma * (m_dfdx * r_x + m_dfdv * m_fixed_r_v);
  m_system.constraints().zero_fixed(m_b);
  const bool converged = solve_reduced(m_b, m_z_v);
  for (const int i : m_system.constraints().fixed_particles()) particle(m_z_v, i) = particle(r_v, i);
  z.tail(n3) = m_z_v;
  z.head(n3) = r_x + m_gamma * m_z_v;
  for (const int i : m_system.constraints().fixed_particles())
    particle(z.head(n3), i) = particle(r_x, i);
  return converged;
}

bool ReducedNewtonSolver::solve_reduced(const Eigen::VectorXd& b, Eigen::VectorXd& z_v) {
  if (m_method == ReducedSolve::sparse_ldlt) {
    z_v = m_ldlt.solve(b);
    return m_ldlt.info() == Eigen::Success;
  }
  // Preconditioned conjugate gradients from z = 0 (Shewchuk 1994, B2), stopping at
  // |b - S z| <= tolerance |b|.
  const Eigen::Index n = b.size() / 3;
  auto precondition = [&](const Eigen::VectorXd& in, Eigen::VectorXd& out) {
    out.resize(in.size());
    for (Eigen::Index i = 0; i < n; ++i)
      particle(out, i) = m_block_inverse[static_cast<std::size_t>(i)] * particle(in, i);
  };
  z_v.setZero(b.size());
  const double b_norm = b.norm();
  if (b_norm == 0.0) return true;
  m_residual = b;
  precondition(m_residual, m_preconditioned);
  m_direction = m_preconditioned;
  double rho = m_residual.dot(m_preconditioned);
  for (int k = 0; k < m_max_iterations; ++k) {
    m_product.noalias() = m_s * m_direction;
    const double alpha = rho / m_direction.dot(m_product);
    z_v += alpha * m_direction;
    m_residual -= alpha * m_product;
    ++m_iterations;
    if (m_residual.norm() <= m_tolerance * b_norm) return true;
    precondition(m_residual, m_preconditioned);
    const double rho_next = m_residual.dot(m_preconditioned);
    m_direction = m_preconditioned + (rho_next / rho) * m_direction;
    rho = rho_next;
  }
  return false;
}

}  // namespace drape
