#include "integrators/newton/exact_stage_jacobian.hpp"

#include <algorithm>

namespace drape {

ExactStageJacobian::ExactStageJacobian(const ClothSystem& system, ForceSplit split)
    : m_system(system), m_split(split) {}

bool ExactStageJacobian::factorize(ConstVecRef x, ConstVecRef v, double gamma, double shift) {
  // dF/dx and dF/dv have the fixed particles' rows zeroed; their columns are dropped below, so
  // a fixed particle's row and column of A are M I (its velocity is no unknown).
  m_system.force_jacobians(x, v, false, m_dfdx, m_dfdv, m_split);
  m_a = -(gamma * gamma) * m_dfdx - gamma * m_dfdv;
  const auto& fixed = m_system.constraints().mask();
  m_a.prune([&](Eigen::Index row, Eigen::Index column, double) {
    return !fixed[static_cast<std::size_t>(row / 3)] && !fixed[static_cast<std::size_t>(column / 3)];
  });
  Eigen::SparseMatrix<double> mass(m_a.rows(), m_a.cols());
  mass.setIdentity();
  // The shift adds to the mass on the diagonal only: the pattern, and so the analysis, is kept.
  m_a += (1.0 + shift) * m_system.particle_mass() * mass;
  // The symbolic analysis (column ordering, elimination tree) depends on the pattern alone,
  // which changes only with the fixed set or the contacts: redone then, not every iteration.
  if (!same_pattern()) {
    m_lu.analyzePattern(m_a);
    m_outer.assign(m_a.outerIndexPtr(), m_a.outerIndexPtr() + m_a.outerSize() + 1);
    m_inner.assign(m_a.innerIndexPtr(), m_a.innerIndexPtr() + m_a.nonZeros());
  }
  m_lu.factorize(m_a);
  return m_lu.info() == Eigen::Success;
}

bool ExactStageJacobian::same_pattern() const {
  return m_a.isCompressed() && m_outer.size() == static_cast<std::size_t>(m_a.outerSize()) + 1 &&
         std::equal(m_outer.begin(), m_outer.end(), m_a.outerIndexPtr()) &&
         m_inner.size() == static_cast<std::size_t>(m_a.nonZeros()) &&
         std::equal(m_inner.begin(), m_inner.end(), m_a.innerIndexPtr());
}

void ExactStageJacobian::newton_direction(const Eigen::VectorXd& g, Eigen::VectorXd& d) {
  m_rhs = -g;
  d = m_lu.solve(m_rhs);
  m_system.constraints().zero_fixed(d);
}

}  // namespace drape
