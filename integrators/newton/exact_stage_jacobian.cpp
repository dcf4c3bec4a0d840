#include "integrators/newton/exact_stage_jacobian.hpp"

namespace drape {

ExactStageJacobian::ExactStageJacobian(const ClothSystem& system, ForceSplit split)
    : m_system(system), m_split(split) {}

bool ExactStageJacobian::factorize(ConstVecRef x, ConstVecRef v, double gamma) {
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
  m_a += m_system.particle_mass() * mass;
  m_lu.compute(m_a);
  return m_lu.info() == Eigen::Success;
}

void ExactStageJacobian::newton_direction(const Eigen::VectorXd& g, Eigen::VectorXd& d) {
  d = m_lu.solve(-g);
  m_system.constraints().zero_fixed(d);
}

}  // namespace drape
