#pragma once
#include <optional>

#include "integrators/interface/integrator.hpp"
#include "integrators/interface/integrator_declaration.hpp"
#include "integrators/interface/integrator_options.hpp"
#include "integrators/newton/converged_step.hpp"
#include "integrators/newton/linearised_step.hpp"
#include "integrators/linear/reduced_newton_solver.hpp"

namespace drape {

/// The graphics community's implicit Euler (Baraff and Witkin 1998, "Large steps in cloth
/// simulation", SIGGRAPH, section 4): one Newton step of backward Euler from (x, v),
///   (M - h dF/dv - h^2 dF/dx) dv = h (F + h dF/dx v),   x += h (v + dv),   v += dv,
/// with the definite Jacobian, fixed particles' dv prescribed (filtered out of the solve) and
/// the 3N system solved by CG preconditioned by a multigrid cycle (`pcg-multigrid`, the
/// default) or by its block diagonal (`pcg-reduced`), both started from the S-orthogonal
/// projection onto the last two steps' dv (CgStart::projected) and run to the relative
/// residual `linear_tolerance` (default 1e-3), or by a sparse LDLT factorisation
/// (`sparse-direct`). Then the projection of docs/model.md section 5. First order,
/// unconditionally stable for the linearised problem; one force evaluation and one Jacobian
/// per step. With `solve` = converged, backward Euler itself: the one stage
/// z = y_n + h f(t_{n+1}, z) solved to convergence by ConvergedStep (converged_step.hpp), a
/// step whose solve fails taken as halves, which separates linearisation error from backward
/// Euler's damping (docs/integrators/implicit-euler.md).
class ImplicitEuler final : public Integrator {
 public:
  /// Reads dt, linear_solver, linear_tolerance and max_linear_iters from `options`.
  ImplicitEuler(ClothSystem& system, const IntegratorOptions& options);
  double step(double t_stop) override;

 private:
  long m_max_steps;
  double m_dt;
  ReducedNewtonSolver m_solver;
  LinearisedStep m_linearised;                // solve = linearised
  std::optional<ConvergedStep> m_converged;  // solve = converged
};

/// implicit-euler's declaration for the registry (integrator_declaration.hpp).
IntegratorDeclaration implicit_euler_declaration();

}  // namespace drape
