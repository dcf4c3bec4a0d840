#pragma once
// Newton's method on the incremental potential of an implicit stage, globalised by a
// backtracking line search (docs/integrators/line-search-newton.md, "Stages as minimisation"; Gast
// et al. 2015; Nocedal and Wright 2006, algorithm 3.1; ipc-toolkit and IPC use the same
// globalisation). Each iteration freezes E_k at the iterate, takes the Newton direction d = -S^-1 g
// of the definite Hessian S (descent, S positive definite; CG solves S only to Eisenstat and
// Walker's forcing term, an inexact Newton, as any CG iterate descends) and halves the step until
// Armijo's condition E_k(v + alpha d) <= E_k(v) + 1e-4 alpha g.d holds. Once a full step was
// accepted, the exact stage Jacobian's direction (ExactStageJacobian) replaces d: quadratic
// convergence near the solution, where S alone converged linearly or, at 100x stiffness, cycled.
// Where A is indefinite (compressed springs, the bending-free sheet buckling) its direction need
// not descend; there A + shift M is factorised instead, the shift of Levenberg and Marquardt grown
// until the direction descends (a trust-region step that follows A's negative curvature, where
// S treats it as zero curvature and creeps: docs/journal/2026-11-25-failing-stages-trace.md, "What
// the failing stages look like"). The local phase's systems are factorised (sparse LU) or, with
// ExactSolve::bicgstab, solved by BiCGSTAB preconditioned by S's preconditioner to the cap of CG's
// forcing term, the LU taking over where BiCGSTAB does not converge. The stage is solved when the
// update's weighted RMS norm (ARKODE's error weights) times rate / (1 - rate), the error it leaves
// at the observed rate, is at most `tolerance` (ARKODE's test, arkStep_NlsConvTest, with that
// factor for min(rate, 1)).
#include <Eigen/Core>
#include <optional>
#include <string>

#include "core/model/cloth_system.hpp"
#include "integrators/newton/exact_stage_jacobian.hpp"
#include "integrators/newton/incremental_potential.hpp"
#include "integrators/linear/reduced_newton_solver.hpp"

namespace drape {

/// What one stage solve did.
struct StageSolve {
  bool converged = false;
  /// Why an unconverged solve stopped: the iteration limit, a line search that found no
  /// decrease in 30 halvings, or a zero gradient with a step still above tolerance.
  const char* stopped_by = "the iteration limit";
  int iterations = 0;   ///< Newton iterations (directions computed)
  long backtracks = 0;  ///< step halvings of the line search
  long rhs_evals = 0;   ///< force evaluations (gradients and the fixed rows)
  long setups = 0;      ///< Hessian evaluations
  /// Directions from A + shift M with a positive Levenberg-Marquardt shift (A's own did not
  /// descend, or the last one needed backtracking).
  int shifted_directions = 0;
  long krylov_iterations = 0;  ///< BiCGSTAB iterations (ExactSolve::bicgstab)
};

/// How the local phase solves (A + shift M) d = -g (`integrator.exact_solve`).
enum class ExactSolve {
  lu,        ///< UMFPACK's sparse LU, every local iteration (the default)
  bicgstab,  ///< BiCGSTAB preconditioned by S's preconditioner, to the forcing term; the LU
             ///< where it does not get there in max_krylov_iterations
};

/// The ExactSolve named `lu` or `bicgstab`; nothing for another name.
std::optional<ExactSolve> exact_solve_named(const std::string& name);
/// "lu, bicgstab", for messages.
std::string exact_solve_names();

/// How a stage solve stops.
struct StageTolerance {
  ConstVecRef weights;  ///< 6N error weights: the update's norm is sqrt(mean((w_i dz_i)^2))
  double tolerance;     ///< largest weighted RMS norm of a converged update
  int max_iterations;
};

/// The line-search Newton minimiser of IncrementalPotential.
class LineSearchNewton {
 public:
  /// `solver` solves with the Hessian S (its split must be `split`).
  LineSearchNewton(const ClothSystem& system, ForceSplit split, ReducedNewtonSolver& solver,
                   ExactSolve exact_solve = ExactSolve::lu);
  // m_precondition calls this object's solver: a copy would call the original's.
  LineSearchNewton(const LineSearchNewton&) = delete;
  LineSearchNewton& operator=(const LineSearchNewton&) = delete;

  /// Solves z = a + gamma f_I(t, z) starting from the guess z (6N), which receives the solution
  /// (the last iterate when not converged).
  StageSolve solve(double t, double gamma, ConstVecRef a, VecRef z, const StageTolerance& stop);
  const IncrementalPotential& potential() const { return m_potential; }

 private:
  /// The direction d = -(A + shift M)^-1 g in m_direction and its slope g.d, with the smallest
  /// shift from `shift` up (tenfold steps) whose factorisation succeeds and whose direction
  /// descends on E_k; `shift` receives it. False when even the largest shift does not.
  bool shifted_exact_direction(ConstVecRef z, double gamma, double forcing, double& shift,
                               double& slope, StageSolve& result);
  /// Armijo backtracking from z along d; false when 30 halvings found no decrease.
  bool line_search(VecRef z, double slope, StageSolve& result);

  const ClothSystem& m_system;
  IncrementalPotential m_potential;
  ReducedNewtonSolver& m_solver;
  ExactStageJacobian m_exact;
  ExactSolve m_exact_solve;
  ExactStageJacobian::Preconditioner m_precondition;
  Eigen::VectorXd m_gradient, m_rhs, m_step, m_v, m_trial, m_direction;
};

}  // namespace drape
