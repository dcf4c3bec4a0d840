#pragma once
// The global step's matrix of Projective Dynamics (Liu et al. 2013, "Fast simulation of
// mass-spring systems", section 4; Bouaziz et al. 2014, "Projective Dynamics", section 3.3)
// over the free particles only: the fixed particles' positions are known at the step's end and
// their columns move to the right side (docs/integrators/projective-dynamics.md).
//
// Every term is isotropic, so the 3N x 3N matrix is A (x) I_3 with the scalar
//     A = (m / h^2 + c_air / h) I + sum_e (k_e + c_s / h) a_e a_e^T + w diag(contact),
// a_e the spring's incidence vector (+1 at i, -1 at j, fixed ends dropped): one scalar sparse
// Cholesky factorisation serves the three coordinates, a third of the nonzeros of the 3N one.
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <vector>

#include "core/cloth/spring_list.hpp"

namespace drape {

/// A of the global step, factored; solves A X = B for the three coordinate columns at once.
class PdGlobalMatrix {
 public:
  /// A of `springs` with contact weight w = `contact_weight`.
  PdGlobalMatrix(const SpringList& springs, double contact_weight);

  /// Numbers the free particles of `fixed` (1 = fixed), assembles A with `diagonal`
  /// = m/h^2 + c_air/h and spring weights k_e + `spring_extra` (c_s/h), and factors it
  /// (symbolic analysis and numeric factorisation). `contact[i]` = 1 adds w to particle i's
  /// diagonal.
  void factor(const std::vector<unsigned char>& fixed, const std::vector<unsigned char>& contact,
              double diagonal, double spring_extra);
  /// Numeric refactorisation with the same fixed set and new contact flags (same pattern).
  void refactor(const std::vector<unsigned char>& contact);

  int num_free() const { return static_cast<int>(m_particles.size()); }
  /// The free particles in the factor's fill-reducing order: slot s holds particle slots()[s].
  const std::vector<int>& slots() const { return m_slot_particle; }
  /// Overwrites z (num_free() rows of 3 interleaved values, in slot order) with A^-1 z: the
  /// factor's triangular sweeps on the three coordinates at once, one pass over L each way.
  void solve_in_place(double* z) const;

 private:
  int index(int i) const { return m_index[static_cast<std::size_t>(i)]; }
  int particle_of(int r) const { return m_particles[static_cast<std::size_t>(r)]; }

  const SpringList& m_springs;
  double m_contact_weight;
  std::vector<int> m_index, m_particles;  // row of a particle (-1: fixed), particle of a row
  std::vector<int> m_slot_particle;
  std::vector<int> m_diagonal_slot;  // per free row: A's value index of its diagonal entry
  Eigen::SparseMatrix<double> m_matrix;
  Eigen::VectorXd m_base_diagonal;   // the diagonal without contact weights
  Eigen::VectorXd m_inverse_d;       // D^-1 of the factor
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>>
      m_factor;
};

}  // namespace drape
