#include "integrators/newton/exact_stage_jacobian.hpp"

#include <algorithm>

namespace drape {

ExactStageJacobian::ExactStageJacobian(const ClothSystem& system, ForceSplit split)
    : m_system(system), m_split(split) {
  // Iterative refinement (UMFPACK's default, up to two steps) costs more solves and residuals
  // a direction; the line search checks each direction's descent and the stage's convergence
  // test its result, so a direction to the factorisation's own accuracy is enough (the 64 x 64
  // sheet's 12 SDIRK2 steps took the same iterations without it:
  // docs/journal/2026-11-24-sdirk2-step-cost.md).
  m_lu.umfpackControl()(UMFPACK_IRSTEP) = 0;
}

void ExactStageJacobian::build_pattern() {
  const auto& fixed = m_system.constraints().mask();
  const auto& springs = m_system.cloth().springs;
  const int n = m_system.num_particles();
  // A fixed particle's row and column are M I (its velocity is no unknown): it keeps its
  // diagonal block and loses its couplings.
  using Triplet = Eigen::Triplet<double>;
  std::vector<Triplet> entries;
  auto add = [&](int row, int col) {
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) entries.emplace_back(3 * row + a, 3 * col + b, 0.0);
  };
  for (int p = 0; p < n; ++p) add(p, p);
  for (Eigen::Index e = 0; e < springs.size(); ++e) {
    const int i = springs.first[e], j = springs.second[e];
    if (fixed[i] || fixed[j]) continue;
    add(i, j);
    add(j, i);
  }
  m_a.resize(3 * n, 3 * n);
  m_a.setFromTriplets(entries.begin(), entries.end());
  m_a.makeCompressed();

  m_diagonal.resize(static_cast<std::size_t>(n));
  for (int p = 0; p < n; ++p) m_diagonal[static_cast<std::size_t>(p)] = slot_of(p, p);
  m_spring.resize(4 * static_cast<std::size_t>(springs.size()));
  const BlockSlot outside{{-1, -1, -1}};
  for (Eigen::Index e = 0; e < springs.size(); ++e) {
    const int i = springs.first[e], j = springs.second[e];
    const bool coupled = !fixed[i] && !fixed[j];
    BlockSlot* slots = &m_spring[4 * static_cast<std::size_t>(e)];
    slots[0] = fixed[i] ? outside : slot_of(i, i);
    slots[1] = coupled ? slot_of(i, j) : outside;
    slots[2] = coupled ? slot_of(j, i) : outside;
    slots[3] = fixed[j] ? outside : slot_of(j, j);
  }
  m_fixed = fixed;
  m_analysed = false;  // analysed at the next factorisation, with values
}

ExactStageJacobian::BlockSlot ExactStageJacobian::slot_of(int row, int col) const {
  BlockSlot slot{};
  for (int b = 0; b < 3; ++b) {
    const Eigen::Index column = 3 * col + b;
    const int* begin = m_a.innerIndexPtr() + m_a.outerIndexPtr()[column];
    const int* end = m_a.innerIndexPtr() + m_a.outerIndexPtr()[column + 1];
    slot.offset[b] = static_cast<int>(std::lower_bound(begin, end, 3 * row) - m_a.innerIndexPtr());
  }
  return slot;
}

void ExactStageJacobian::add_block(const BlockSlot& slot, double scale, const Mat3& block) {
  if (slot.offset[0] < 0) return;
  double* values = m_a.valuePtr();
  for (int b = 0; b < 3; ++b)
    for (int a = 0; a < 3; ++a) values[slot.offset[b] + a] += scale * block(a, b);
}

void ExactStageJacobian::form(ConstVecRef x, ConstVecRef v, double gamma, double shift) {
  if (m_diagonal.empty() || m_fixed != m_system.constraints().mask()) build_pattern();
  // A = (1 + shift) M - gamma dF/dv - gamma^2 dF/dx; spring e's blocks J enter dF as
  // [-J J; J -J] (cloth_system.hpp, JacobianBlocks), so A receives [J -J; -J J] times
  // gamma^2 (positions) and gamma (velocities), on free rows only.
  m_system.force_jacobian_blocks(x, v, false, m_split, m_blocks);
  std::fill(m_a.valuePtr(), m_a.valuePtr() + m_a.nonZeros(), 0.0);
  const double mass = (1.0 + shift) * m_system.particle_mass();
  const double g2 = gamma * gamma;
  for (std::size_t p = 0; p < m_diagonal.size(); ++p) {
    const BlockSlot& slot = m_diagonal[p];
    for (int b = 0; b < 3; ++b) m_a.valuePtr()[slot.offset[b] + b] = mass;
    if (m_fixed[p]) continue;
    add_block(slot, -g2, m_blocks.particle_x[p]);
    add_block(slot, -gamma, m_blocks.particle_v[p]);
  }
  for (std::size_t e = 0; e < m_blocks.spring_x.size(); ++e) {
    const BlockSlot* slots = &m_spring[4 * e];
    for (int k = 0; k < 4; ++k) {
      const double sign = (k == 0 || k == 3) ? 1.0 : -1.0;
      add_block(slots[k], sign * g2, m_blocks.spring_x[e]);
      add_block(slots[k], sign * gamma, m_blocks.spring_v[e]);
    }
  }
}

bool ExactStageJacobian::factorize(ConstVecRef x, ConstVecRef v, double gamma, double shift) {
  form(x, v, gamma, shift);
  return factorize();
}

bool ExactStageJacobian::factorize() {
  // The analysis runs on the first values of a pattern, not on the zeros build_pattern() left:
  // UMFPACK's symbolic phase reads the values too (its strategy and diagonal preference look at
  // which diagonal entries are nonzero), and an analysis of zeros made the 64 x 64 sheet's
  // directions so poor that its 12 SDIRK2 steps needed 45 halvings instead of none.
  if (!m_analysed) {
    m_lu.analyzePattern(m_a);
    m_analysed = true;
  }
  m_lu.factorize(m_a);
  return m_lu.info() == Eigen::Success;
}

void ExactStageJacobian::newton_direction(const Eigen::VectorXd& g, Eigen::VectorXd& d) {
  m_rhs = -g;
  d = m_lu.solve(m_rhs);
  m_system.constraints().zero_fixed(d);
}

bool ExactStageJacobian::krylov_direction(const Eigen::VectorXd& g, Eigen::VectorXd& d,
                                          const Preconditioner& preconditioner, double tolerance,
                                          int max_iterations, long& iterations) {
  m_krylov.preconditioner().apply = &preconditioner;
  m_krylov.compute(m_a);
  m_krylov.setTolerance(tolerance);
  m_krylov.setMaxIterations(max_iterations);
  m_rhs = -g;
  d = m_krylov.solve(m_rhs);
  m_system.constraints().zero_fixed(d);
  iterations += m_krylov.iterations();
  return m_krylov.info() == Eigen::Success;
}

}  // namespace drape
