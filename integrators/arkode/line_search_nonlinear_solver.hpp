#pragma once
// ARKODE's implicit stages solved by LineSearchNewton, through ARKODE's custom nonlinear
// solver interface (SUNDIALS 6.4.1 user guide, "SUNNonlinearSolver": a ROOTFIND solver given to
// ARKStepSetNonlinearSolver). ARKODE's stage in correction form is
//     zcor - gamma f_I(t, zpred + zcor) - sdata = 0   (arkode_arkstep_nls.c),
// that is z = a + gamma f_I(t, z) with a = zpred + sdata, read with
// ARKStepGetNonlinearSystemData: the stage of IncrementalPotential. The solve returns zcor =
// z - zpred; a stage that does not converge is a recoverable failure (SUN_NLS_CONV_RECVR), on
// which ARKODE shrinks an adaptive step and drapelab halves a fixed one.
#include <memory>
#include <sundials/sundials_nonlinearsolver.h>

#include "integrators/newton/line_search_newton.hpp"

namespace drape {

namespace detail {
struct NonlinearSolverDeleter {
  void operator()(SUNNonlinearSolver solver) const { SUNNonlinSolFree(solver); }
};
/// A SUNDIALS nonlinear solver.
using NonlinearSolverHandle =
    std::unique_ptr<std::remove_pointer_t<SUNNonlinearSolver>, NonlinearSolverDeleter>;
}  // namespace detail

/// A SUNNonlinearSolver whose solve is LineSearchNewton::solve on ARKODE's current stage.
class LineSearchNonlinearSolver {
 public:
  /// `newton` must outlive this object; the object must outlive the ARKODE memory using it.
  LineSearchNonlinearSolver(LineSearchNewton& newton, SUNContext context);
  LineSearchNonlinearSolver(const LineSearchNonlinearSolver&) = delete;
  LineSearchNonlinearSolver& operator=(const LineSearchNonlinearSolver&) = delete;

  SUNNonlinearSolver get() const { return m_solver.get(); }
  /// Totals over every solve so far.
  long backtracks() const { return m_backtracks; }
  long rhs_evals() const { return m_rhs_evals; }
  long setups() const { return m_setups; }
  long krylov_iterations() const { return m_krylov_iterations; }

 private:
  static LineSearchNonlinearSolver& self(SUNNonlinearSolver solver);
  static int solve(SUNNonlinearSolver solver, N_Vector predictor, N_Vector correction,
                   N_Vector weights, sunrealtype tolerance, sunbooleantype, void* arkode_mem);

  LineSearchNewton& m_newton;
  detail::NonlinearSolverHandle m_solver;
  int m_max_iterations = 3;  // ARKODE's default until it calls setmaxiters
  // ARKODE adds these to its own totals after every solve: they describe the last one.
  long m_last_iterations = 0, m_last_failures = 0;
  long m_backtracks = 0, m_rhs_evals = 0, m_setups = 0, m_krylov_iterations = 0;
  Eigen::VectorXd m_known, m_stage;
};

}  // namespace drape
