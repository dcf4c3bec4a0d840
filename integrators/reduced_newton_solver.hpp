#pragma once
// Newton's linear system of an implicit step of the cloth ODE, solved on the 3N velocities.
//
// With y = [x; v] and J = [0 I; M^-1 K  M^-1 D] on the free particles (K = dF/dx, D = dF/dv;
// a fixed particle's rows of J are zero because its right-hand side is prescribed), the system
// (I - gamma J) z = r reduces exactly to
//     S z_v = M r_v + gamma K r_x + gamma D r_v|fixed,   S = M - gamma D - gamma^2 K,
// on the free particles, then z_x = r_x + gamma z_v; a fixed particle keeps z = r. S uses the
// definite Jacobian (forces.hpp), so it is symmetric positive definite: conjugate gradients or
// a sparse Cholesky factorisation solve it (Baraff and Witkin 1998, section 5).
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <optional>
#include <string>
#include <vector>

#include "core/cloth_system.hpp"

namespace drape {

/// How the reduced system S is solved.
enum class ReducedSolve {
  conjugate_gradients,  ///< `pcg-reduced`: block-Jacobi preconditioned CG on S
  sparse_ldlt,          ///< `sparse-direct`: Eigen's SimplicialLDLT factorisation of S
};

/// The method `integrator.linear_solver` names, or nothing for an unknown name.
std::optional<ReducedSolve> reduced_solve_named(const std::string& name);
/// Every accepted `integrator.linear_solver` name, comma separated (for error messages).
std::string reduced_solve_names();

/// Solves (I - gamma J) z = r for the cloth ODE through the reduced 3N system S.
class ReducedNewtonSolver {
 public:
  /// `split` selects the forces whose Jacobian J holds (all, or the springs for IMEX).
  ReducedNewtonSolver(const ClothSystem& system, ReducedSolve method, ForceSplit split,
                      double tolerance, int max_iterations);

  /// Assembles the definite K and D at (x, v) and forms S for `gamma`.
  void update(ConstVecRef x, ConstVecRef v, double gamma);
  /// Forms S for a new gamma from the last K and D.
  void set_gamma(double gamma);
  ReducedSolve method() const { return m_method; }
  /// False until update() runs, and again after invalidate().
  bool has_jacobian() const { return m_has_jacobian; }
  /// Forgets K and D (the constraints changed): the next setup must call update().
  void invalidate() { m_has_jacobian = false; }
  /// z = (I - gamma J)^-1 r for 6N vectors; false when CG stopped before its tolerance (z is
  /// then its last iterate).
  bool solve(ConstVecRef r, VecRef z);
  /// CG iterations over all solves so far (0 for the direct solve).
  long iterations() const { return m_iterations; }

 private:
  void form_system();
  bool solve_reduced(const Eigen::VectorXd& b, Eigen::VectorXd& z_v);

  const ClothSystem& m_system;
  ReducedSolve m_method;
  ForceSplit m_split;
  double m_tolerance;
  int m_max_iterations;
  double m_gamma = 0.0;
  bool m_has_jacobian = false;
  long m_iterations = 0;
  Eigen::SparseMatrix<double> m_dfdx, m_dfdv, m_s;
  std::vector<Mat3> m_block_inverse;  // block-Jacobi preconditioner of CG
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> m_ldlt;
  Eigen::VectorXd m_b, m_z_v, m_fixed_r_v, m_residual, m_direction, m_preconditioned, m_product;
};

}  // namespace drape
