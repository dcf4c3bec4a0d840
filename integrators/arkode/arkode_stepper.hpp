#pragma once
#include <string>
#include <optional>
#include <vector>

#include "integrators/arkode/arkode_tables.hpp"
#include "integrators/arkode/line_search_nonlinear_solver.hpp"
#include "integrators/interface/integrator.hpp"
#include "integrators/interface/integrator_declaration.hpp"
#include "integrators/interface/integrator_options.hpp"
#include "integrators/linear/reduced_newton_solver.hpp"
#include "integrators/arkode/sundials_handles.hpp"

namespace drape {

/// arkode-erk, arkode-dirk and arkode-imex: ARKODE's additive Runge-Kutta stepper ARKStep
/// (Kennedy and Carpenter 2003, Appl. Numer. Math. 44; Reynolds et al. 2023, ACM TOMS 49) on
/// y' = f_E(t, y) + f_I(t, y), stage i and step
///   z_i = y_n + h sum_{j<i} A^E_ij f_E(t_n + c^E_j h, z_j) + h sum_{j<=i} A^I_ij f_I(t_n + c^I_j
/// h, z_j)
///   y_{n+1} = y_n + h sum_i (b^E_i f_E(t_n + c^E_i h, z_i) + b^I_i f_I(t_n + c^I_i h, z_i)).
/// arkode-erk: f_E = y', no f_I (ARKStep's explicit mode, right for every table, unlike ERKStep
/// 6.4.1). arkode-dirk: f_I = y', no f_E. arkode-imex: f_I = [v; M^-1 F_springs] (stiff),
/// f_E = [0; M^-1 (gravity + air damping + collision)]. Implicit stages are solved, by default
/// (`nonlinear_solver` = newton), by ARKODE's Newton method with GMRES, the analytic
/// Jacobian-times-vector and the reduced 3N system as the preconditioner
/// (reduced_newton_solver.hpp), or (`line-search`) as the minimisation of their incremental
/// potential by Newton's method with a line search (line_search_nonlinear_solver.hpp). Fixed or
/// error-controlled steps.
///
/// arkode-dirk fixes the contact set over each step (Collision::pair_contacts): each cloth
/// particle keeps the contact of the step start (its nearest object particle, or the surface),
/// linearised there, paired again after every accepted step. A switch of the nearest object
/// particle (or of the surface's piece) between Newton iterates made the collision force jump
/// and Newton cycle (docs/integrators/arkode.md). arkode-erk and arkode-imex with the collision
/// explicit (its default split) evaluate the unpaired model.
class ArkodeStepper final : public Integrator {
 public:
  /// `options` must have passed validate_integrator_choice().
  ArkodeStepper(ClothSystem& system, ArkodeKind kind, const IntegratorOptions& options);
  /// Leaves the system's collision unpaired, as every other integrator expects it.
  ~ArkodeStepper() override;
  void reset(double t, const Eigen::VectorXd& y) override;
  double step(double t_stop) override;

 private:
  /// ARKODE's cumulative counters, read after every step to update m_counters.
  struct ArkodeCounts {
    long steps = 0, attempts = 0, rhs_evals = 0, newton_iters = 0, newton_failures = 0,
         linear_iters = 0, linear_failures = 0, setups = 0, error_test_failures = 0,
         backtracks = 0;
  };

  /// The forces f_I and f_E evaluate.
  struct Split {
    ForceSplit implicit_part, explicit_part;
  };
  static Split split_of(ArkodeKind kind, const IntegratorOptions& options);

  void create(double t);
  void set_up_newton();
  void set_up_linear_solver();
  void restart(double initial_step);
  /// One ARKODE step towards `target`, projected; throws IntegratorFailure.
  void evolve(double target);
  /// Fixed steps up to t_end, a failed one halved up to `halvings_left` times.
  void cover_fixed(double t_end, int halvings_left);
  /// One fixed step of exactly t_end - m_t; throws IntegratorFailure.
  void evolve_fixed(double t_end);
  ArkodeCounts read_counts() const;
  void accumulate_counters();
  /// Whether the collision force is inside Newton's stage equations (arkode-dirk, and
  /// arkode-imex with the contact implicit).
  bool pairs_contacts() const {
    return m_kind != ArkodeKind::explicit_rk && m_split.implicit_part.with_collision;
  }

  static int explicit_rhs(sunrealtype t, N_Vector y, N_Vector y_dot, void* self);
  static int implicit_rhs(sunrealtype t, N_Vector y, N_Vector y_dot, void* self);
  static int postprocess_step(sunrealtype t, N_Vector y, void* self);
  static void record_error(int code, const char* module, const char* function, char* message,
                           void* self);
  static int jacobian_times(N_Vector w, N_Vector j_w, sunrealtype t, N_Vector y, N_Vector f_y,
                            void* self, N_Vector tmp);
  static int preconditioner_setup(sunrealtype t, N_Vector y, N_Vector f_y, sunbooleantype jok,
                                  sunbooleantype* jcur, sunrealtype gamma, void* self);
  static int preconditioner_solve(sunrealtype t, N_Vector y, N_Vector f_y, N_Vector r,
                                  N_Vector z, sunrealtype gamma, sunrealtype delta, int lr,
                                  void* self);

  ArkodeKind m_kind;
  IntegratorOptions m_options;
  Split m_split;  // chosen once by split_of: every right-hand side reads it
  const ArkodeTable& m_table;
  std::optional<ReducedNewtonSolver> m_reduced;  // implicit kinds only
  std::optional<LineSearchNewton> m_line_search;  // with nonlinear_solver = line-search
  int m_corrections = 0;  // penetrations corrected by postprocess_step during the last step
  std::string m_arkode_message;  // ARKODE's explanation of the last failure
  ArkodeCounts m_seen;    // ARKODE's counters when m_counters was last updated
  long m_cg_seen = 0;
  // Declared in the order of construction; destroyed in reverse (ARKODE before its solver).
  sundials::Context m_context;
  detail::NVectorHandle m_y_vector;  // views Integrator::m_y
  detail::LinearSolverHandle m_linear_solver;
  std::unique_ptr<LineSearchNonlinearSolver> m_nonlinear_solver;
  detail::ArkodeHandle m_arkode;
};

/// The declarations of arkode-erk, arkode-dirk and arkode-imex for the registry
/// (arkode_integrators.hpp).
std::vector<IntegratorDeclaration> arkode_declarations();

}  // namespace drape
