#include "integrators/projective_dynamics/pd_global_matrix.hpp"

#include <algorithm>
#include <stdexcept>

namespace drape {

PdGlobalMatrix::PdGlobalMatrix(const SpringList& springs, double contact_weight)
    : m_springs(springs), m_contact_weight(contact_weight) {}

void PdGlobalMatrix::factor(const std::vector<unsigned char>& fixed,
                            const std::vector<unsigned char>& contact, double diagonal,
                            double spring_extra) {
  const int n = static_cast<int>(fixed.size());
  m_index.assign(fixed.size(), -1);
  m_particles.clear();
  for (int i = 0; i < n; ++i)
    if (!fixed[static_cast<std::size_t>(i)]) {
      m_index[static_cast<std::size_t>(i)] = static_cast<int>(m_particles.size());
      m_particles.push_back(i);
    }
  const int rows = num_free();
  m_slot_particle.clear();
  if (rows == 0) return;  // every particle fixed: nothing to solve
  // Lower triangle only: SimplicialLDLT<Lower> reads nothing else.
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<std::size_t>(rows + m_springs.size()));
  m_base_diagonal = Eigen::VectorXd::Constant(rows, diagonal);
  for (Eigen::Index e = 0; e < m_springs.size(); ++e) {
    const double weight = m_springs.stiffness[e] + spring_extra;
    const int a = index(m_springs.first[e]), b = index(m_springs.second[e]);
    if (a >= 0) m_base_diagonal[a] += weight;
    if (b >= 0) m_base_diagonal[b] += weight;
    if (a >= 0 && b >= 0) triplets.emplace_back(std::max(a, b), std::min(a, b), -weight);
  }
  for (int r = 0; r < rows; ++r) triplets.emplace_back(r, r, 0.0);
  m_matrix.resize(rows, rows);
  m_matrix.setFromTriplets(triplets.begin(), triplets.end());
  m_matrix.makeCompressed();
  m_diagonal_slot.assign(static_cast<std::size_t>(rows), -1);
  for (int c = 0; c < rows; ++c)
    for (int k = m_matrix.outerIndexPtr()[c]; k < m_matrix.outerIndexPtr()[c + 1]; ++k)
      if (m_matrix.innerIndexPtr()[k] == c) m_diagonal_slot[static_cast<std::size_t>(c)] = k;
  m_factor.analyzePattern(m_matrix);
  // P A P^T = L D L^T: row r of A is slot P(r) of the factor's order.
  const auto& permutation = m_factor.permutationP().indices();
  m_slot_particle.assign(static_cast<std::size_t>(rows), -1);
  for (int r = 0; r < rows; ++r)
    m_slot_particle[static_cast<std::size_t>(permutation[r])] = particle_of(r);
  refactor(contact);
}

void PdGlobalMatrix::refactor(const std::vector<unsigned char>& contact) {
  double* values = m_matrix.valuePtr();
  for (int r = 0; r < num_free(); ++r)
    values[m_diagonal_slot[static_cast<std::size_t>(r)]] =
        m_base_diagonal[r] + (contact[static_cast<std::size_t>(particle_of(r))] ? m_contact_weight : 0.0);
  m_factor.factorize(m_matrix);
  // A is a weighted graph Laplacian plus a positive diagonal: positive definite whenever the
  // mass is positive, so a failure is a programming error (or a non-finite parameter).
  if (m_factor.info() != Eigen::Success)
    throw std::runtime_error("projective-dynamics: the global matrix is not positive definite");
  m_inverse_d = m_factor.vectorD().cwiseInverse();
}

void PdGlobalMatrix::solve_in_place(double* z) const {
  if (num_free() == 0) return;
  // L is stored by columns, strictly lower (unit diagonal implicit) in SimplicialLDLT.
  const auto& l = m_factor.matrixL().nestedExpression();
  const int* start = l.outerIndexPtr();
  const int* row = l.innerIndexPtr();
  const double* value = l.valuePtr();
  const double* inverse_d = m_inverse_d.data();
  const int n = num_free();
  for (int j = 0; j < n; ++j) {  // L z' = z, column by column
    const double z0 = z[3 * j], z1 = z[3 * j + 1], z2 = z[3 * j + 2];
    for (int k = start[j]; k < start[j + 1]; ++k) {
      double* zi = z + 3 * row[k];
      zi[0] -= value[k] * z0;
      zi[1] -= value[k] * z1;
      zi[2] -= value[k] * z2;
    }
  }
  for (int j = n - 1; j >= 0; --j) {  // L^T z = D^-1 z', row j of L^T is column j of L
    double z0 = z[3 * j] * inverse_d[j], z1 = z[3 * j + 1] * inverse_d[j],
           z2 = z[3 * j + 2] * inverse_d[j];
    for (int k = start[j]; k < start[j + 1]; ++k) {
      const double* zi = z + 3 * row[k];
      z0 -= value[k] * zi[0];
      z1 -= value[k] * zi[1];
      z2 -= value[k] * zi[2];
    }
    z[3 * j] = z0;
    z[3 * j + 1] = z1;
    z[3 * j + 2] = z2;
  }
}

}  // namespace drape
