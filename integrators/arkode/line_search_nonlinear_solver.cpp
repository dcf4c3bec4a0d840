#include "integrators/arkode/line_search_nonlinear_solver.hpp"

#include <arkode/arkode_arkstep.h>

#include "integrators/arkode/sundials_handles.hpp"

namespace drape {

using detail::view;

LineSearchNonlinearSolver::LineSearchNonlinearSolver(LineSearchNewton& newton,
                                                     SUNContext context)
    : m_newton(newton),
      m_solver(detail::check_created(SUNNonlinSolNewEmpty(context), "SUNNonlinSolNewEmpty")) {
  SUNNonlinearSolver s = m_solver.get();
  s->content = this;
  s->ops->gettype = [](SUNNonlinearSolver) { return SUNNONLINEARSOLVER_ROOTFIND; };
  s->ops->solve = solve;
  // The content is this object, not malloc'ed memory: only the empty shell is freed.
  s->ops->free = [](SUNNonlinearSolver solver) {
    solver->content = nullptr;
    SUNNonlinSolFreeEmpty(solver);
    return SUN_NLS_SUCCESS;
  };
  // ARKODE requires a system function; the stage is read from ARKODE itself, so it is unused.
  s->ops->setsysfn = [](SUNNonlinearSolver, SUNNonlinSolSysFn) { return SUN_NLS_SUCCESS; };
  // ARKODE's convergence test (arkStep_NlsConvTest) keeps a convergence rate that rejects the
  // growing residual of the first iterations: LineSearchNewton applies its own update test.
  s->ops->setctestfn = [](SUNNonlinearSolver, SUNNonlinSolConvTestFn, void*) {
    return SUN_NLS_SUCCESS;
  };
  s->ops->setmaxiters = [](SUNNonlinearSolver solver, int iterations) {
    self(solver).m_max_iterations = iterations;
    return SUN_NLS_SUCCESS;
  };
  s->ops->getnumiters = [](SUNNonlinearSolver solver, long* iterations) {
    *iterations = self(solver).m_last_iterations;
    return SUN_NLS_SUCCESS;
  };
  s->ops->getcuriter = [](SUNNonlinearSolver solver, int* iteration) {
    *iteration = static_cast<int>(self(solver).m_last_iterations);
    return SUN_NLS_SUCCESS;
  };
  s->ops->getnumconvfails = [](SUNNonlinearSolver solver, long* failures) {
    *failures = self(solver).m_last_failures;
    return SUN_NLS_SUCCESS;
  };
}

LineSearchNonlinearSolver& LineSearchNonlinearSolver::self(SUNNonlinearSolver solver) {
  return *static_cast<LineSearchNonlinearSolver*>(solver->content);
}

int LineSearchNonlinearSolver::solve(SUNNonlinearSolver solver, N_Vector predictor,
                                     N_Vector correction, N_Vector weights,
                                     sunrealtype tolerance, sunbooleantype, void* arkode_mem) {
  LineSearchNonlinearSolver& me = self(solver);
  sunrealtype t = 0.0, gamma = 0.0;
  N_Vector zpred = nullptr, z = nullptr, fi = nullptr, sdata = nullptr;
  void* user_data = nullptr;
  if (ARKStepGetNonlinearSystemData(arkode_mem, &t, &zpred, &z, &fi, &gamma, &sdata,
                                    &user_data) != ARK_SUCCESS)
    return SUN_NLS_MEM_NULL;
  const VecMap guess = view(correction), start = view(predictor);
  me.m_known = view(zpred) + view(sdata);
  me.m_stage = start + guess;
  const StageSolve result = me.m_newton.solve(
      t, gamma, me.m_known, me.m_stage,
      StageTolerance{view(weights), tolerance, me.m_max_iterations});
  me.m_last_iterations = result.iterations;
  me.m_last_failures = result.converged ? 0 : 1;
  me.m_backtracks += result.backtracks;
  me.m_rhs_evals += result.rhs_evals;
  me.m_setups += result.setups;
  me.m_krylov_iterations += result.krylov_iterations;
  if (!result.converged) return SUN_NLS_CONV_RECVR;
  VecMap out = view(correction);
  out = me.m_stage - start;
  return SUN_NLS_SUCCESS;
}

}  // namespace drape
