#pragma once
#include <optional>

#include "integrators/interface/integrator.hpp"
#include "integrators/interface/integrator_declaration.hpp"
#include "integrators/interface/integrator_options.hpp"
#include "integrators/newton/converged_step.hpp"
#include "integrators/newton/linearised_step.hpp"
#include "integrators/linear/reduced_newton_solver.hpp"

namespace drape {

/// Choi and Ko's cloth integrator (2002, "Stable but responsive cloth", SIGGRAPH, section 3):
/// the second-order backward differentiation formula
///   x_{n+1} - 4/3 x_n + 1/3 x_{n-1} = 2/3 h v_{n+1},
///   v_{n+1} - 4/3 v_n + 1/3 v_{n-1} = 2/3 h M^-1 F(x_{n+1}, v_{n+1}),
/// solved by one Newton iteration a step, one solve of the 3N velocity system
///   (M - gamma D - gamma^2 K) dv = M r_v + gamma K r_x,   dx = r_x + gamma dv,
/// with the definite Jacobian and the linear solvers of implicit-euler (linearised_step.hpp).
/// By default (`linearise_about` = predictor) the iteration starts from the predictor
/// y_p = y_n + w (y_n - y_{n-1}), the line through the last two points, with f and the Jacobian
/// taken there, r = gamma f(y_p) + y_n + d - y_p, as BDF codes start their Newton iteration
/// from the explicitly predicted value (SUNDIALS CVODE user guide, "Mathematical
/// considerations"); `linearise_about` = current starts from y_n as Choi and Ko do,
/// r = gamma f(y_n) + d.
/// Steps of unequal size (one cut short by an output or event time) use the variable-step
/// formula (Hairer, Norsett and Wanner, "Solving ODEs I", section III.5): with
/// w = h_{n+1} / h_n, gamma = h_{n+1} (1 + w) / (1 + 2w) and d = w^2 / (1 + 2w) (y_n - y_{n-1})
/// (equal steps: gamma = 2/3 h, d = (y_n - y_{n-1}) / 3).
/// Started, and restarted at every reset() (events), by one linearised implicit Euler step,
/// from the predictor the body forces' step (v_p = v_n + h a_body, x_p = x_n + h v_p; gravity
/// and air damping, not the stiff springs), or from y_n with linearise_about = current.
/// With `solve` = converged, the step's equation itself, y_{n+1} = a + gamma f(y_{n+1}) with
/// a = y_n + d, solved by the line-search Newton to ARKODE's test (ConvergedStep); the start and
/// restarts are converged backward Euler steps, and a step whose solve fails is taken by
/// converged backward Euler (halved as implicit-euler's, the history kept).
/// Second order (the iteration's error is third order locally; from the predictor, which is
/// O(h^2) from the solution, the step is BDF2's own to a small fraction of its error),
/// A-stable for the linear problem; one force evaluation (one more, of the body forces, at a
/// start from the predictor) and one Jacobian
/// per step. Fixed particles are prescribed; then the projection of docs/model.md section 5.
class Bdf2 final : public Integrator {
 public:
  /// Reads dt, max_steps, linear_solver, linear_tolerance, max_linear_iters, solve and
  /// linearise_about from `options` (and with solve = converged the keys ConvergedStep reads).
  Bdf2(ClothSystem& system, const IntegratorOptions& options);
  void reset(double t, const Eigen::VectorXd& y) override;
  double step(double t_stop) override;

 private:
  /// The step from m_t to t_next solved to convergence (with history: BDF2's equation with
  /// `gamma`; without: backward Euler's), projected.
  void converged_step(double t_next, double gamma);
  /// The linearised step's start from the predictor, y = z_0, and m_known = a - z_0: with
  /// history (ratio w) the extrapolation, without it the body forces' step of size h.
  void predict(double t_next, double h, double w);

  double m_dt;
  long m_max_steps;
  ReducedNewtonSolver m_solver;
  LinearisedStep m_linearised;
  std::optional<ConvergedStep> m_converged;  // solve = converged
  // The history point y_{n-1} at m_previous_t, valid while m_has_history.
  Eigen::VectorXd m_previous;
  double m_previous_t = 0.0;
  bool m_has_history = false;
  bool m_from_predictor;  // linearise_about = predictor
  Eigen::VectorXd m_start, m_history_term, m_known;  // y_n, d, a = y_n + d
};

/// bdf2's declaration for the registry (integrator_declaration.hpp).
IntegratorDeclaration bdf2_declaration();

}  // namespace drape
