#include "integrators/arkode/arkode_stepper.hpp"

#include "integrators/arkode/arkode_integrators.hpp"
#include "integrators/arkode/butcher_tableau.hpp"

#include <sunlinsol/sunlinsol_spfgmr.h>
#include <sunlinsol/sunlinsol_spgmr.h>

#include <cassert>
#include <sstream>
#include <stdexcept>

namespace drape {

using detail::check_sundials;
using detail::view;

namespace {

// First step of an adaptive run without integrator.dt: ARKODE's own estimate was 6e-12 s on a
// spring chain (docs/findings/energy_gaining_tables.md), far below any cloth time scale.
constexpr double default_initial_step = 1e-4;
// GMRES needs few iterations with the reduced-system preconditioner (1 to 3 on a hanging
// cloth; compressed springs, whose definite Jacobian differs most from the exact one, need
// more); this bounds the Krylov basis to 20 vectors of 6N doubles.
constexpr int krylov_dimension = 20;

ArkodeStepper& self_of(void* data) { return *static_cast<ArkodeStepper*>(data); }

int check_linear(int flag, const char* call) {
  return check_sundials(flag, call, ARKStepGetLinReturnFlagName);
}

}  // namespace

ArkodeStepper::ArkodeStepper(ClothSystem& system, ArkodeKind kind,
                             const IntegratorOptions& options)
    : Integrator(system),
      m_kind(kind),
      m_options(options),
      m_split(split_of(kind, options)),
      m_table(*[&] {
        // An inline table has no ARKODE name: create() builds it from the options.
        static const ArkodeTable user{"user", ArkodeKind::diagonally_implicit, "", ""};
        if (!options.user_table.is_null()) return &user;
        const ArkodeTable* table = find_arkode_table(
            options.table.empty() ? default_arkode_table(kind) : options.table, kind);
        if (!table) throw std::logic_error("ArkodeStepper: unvalidated table " + options.table);
        return table;
      }()) {
  const NamedKeys& declared = arkode_integrator(kind).named_keys;
  if (kind != ArkodeKind::explicit_rk)
    m_reduced.emplace(system, *reduced_solve_named(linear_solver_of(options, declared)),
                      m_split.implicit_part, linear_tolerance_of(options, declared),
                      options.max_linear_iters);
  if (m_reduced && uses_line_search(options, declared))
    m_line_search.emplace(system, m_split.implicit_part, *m_reduced,
                          *exact_solve_named(exact_solve_of(options)));
  // The N_Vector views m_y for the whole life of the stepper: m_y keeps this size and buffer.
  m_y = Eigen::VectorXd::Zero(system.size());
  m_y_vector = detail::wrap_vector(m_y, m_context);
}

ArkodeStepper::~ArkodeStepper() {
  if (pairs_contacts()) m_system.collision().unpair_contacts();
}

// arkode-imex's split (docs/model.md section 5): the springs implicit, and with
// `imex_split = springs+collision` the contact force too; what is left is explicit. The other
// kinds have one part, which evaluates every force. The smooth Coulomb force (docs/friction.md;
// nothing with collision.friction = 0), a stiff damper of 2 mu lambda / epsilon_v at rest, is
// with the implicit part wherever there is one.
ArkodeStepper::Split ArkodeStepper::split_of(ArkodeKind kind, const IntegratorOptions& options) {
  Split split{ForceSplit::all, ForceSplit::all};
  if (kind == ArkodeKind::imex && options.imex_split == "springs+collision")
    split = {ForceSplit::springs_and_collision, ForceSplit::body};
  else if (kind == ArkodeKind::imex)
    split = {ForceSplit::springs, ForceSplit::non_springs};
  (kind == ArkodeKind::explicit_rk ? split.explicit_part : split.implicit_part)
      .with_smooth_friction = true;
  return split;
}

void ArkodeStepper::reset(double t, const Eigen::VectorXd& y) {
  assert(y.size() == m_y.size());
  Integrator::reset(t, y);  // same size: copies into the buffer that m_y_vector views
  // The constraints may have changed: K and D have other zero rows now.
  if (m_reduced) m_reduced->invalidate();
  if (pairs_contacts()) m_system.collision().pair_contacts(positions());
  if (!m_arkode)
    create(t);
  else
    restart(m_options.dt > 0.0 ? m_options.dt : default_initial_step);
}

void ArkodeStepper::create(double t) {
  const bool has_explicit = m_kind != ArkodeKind::diagonally_implicit;
  const bool has_implicit = m_kind != ArkodeKind::explicit_rk;
  m_arkode.reset(detail::check_created(
      ARKStepCreate(has_explicit ? explicit_rhs : nullptr, has_implicit ? implicit_rhs : nullptr,
                    t, m_y_vector.get(), m_context),
      "ARKStepCreate"));
  void* mem = m_arkode.get();
  check_sundials(ARKStepSetUserData(mem, this), "ARKStepSetUserData");
  // ARKODE would print its failures to stderr; they go into the IntegratorFailure instead.
  check_sundials(ARKStepSetErrHandlerFn(mem, record_error, this), "ARKStepSetErrHandlerFn");
  // The tolerances also set Newton's stopping test, so fixed-step runs need them too.
  check_sundials(ARKStepSStolerances(mem, m_options.rtol, m_options.atol), "ARKStepSStolerances");
  if (m_options.adaptive) {
    check_sundials(ARKStepSetInitStep(mem, m_options.dt > 0.0 ? m_options.dt : default_initial_step),
                   "ARKStepSetInitStep");
    if (m_options.max_dt > 0.0)
      check_sundials(ARKStepSetMaxStep(mem, m_options.max_dt), "ARKStepSetMaxStep");
  } else {
    check_sundials(ARKStepSetFixedStep(mem, m_options.dt), "ARKStepSetFixedStep");
  }
  check_sundials(ARKStepSetMaxNumSteps(mem, m_options.max_steps), "ARKStepSetMaxNumSteps");
  const detail::ButcherTableHandle explicit_table = detail::load_explicit_table(m_table);
  const detail::ButcherTableHandle implicit_table =
      m_options.user_table.is_null()
          ? detail::load_implicit_table(m_table)
          : detail::create_butcher_table(
                read_butcher_tableau(m_options.user_table, "options", "integrator.table"));
  const ARKodeButcherTable main = implicit_table ? implicit_table.get() : explicit_table.get();
  check_sundials(ARKStepSetTables(mem, main->q, main->p, implicit_table.get(), explicit_table.get()),
                 "ARKStepSetTables");
  check_sundials(ARKStepSetPostprocessStepFn(mem, postprocess_step),
                 "ARKStepSetPostprocessStepFn");
  if (has_implicit) set_up_newton();
  m_seen = read_counts();
}

void ArkodeStepper::set_up_newton() {
  void* mem = m_arkode.get();
  if (m_line_search) {
    m_nonlinear_solver = std::make_unique<LineSearchNonlinearSolver>(*m_line_search, m_context);
    check_sundials(ARKStepSetNonlinearSolver(mem, m_nonlinear_solver->get()),
                   "ARKStepSetNonlinearSolver");
  } else {
    set_up_linear_solver();
  }
  check_sundials(
      ARKStepSetMaxNonlinIters(mem, max_newton_iters_of(m_options, m_line_search.has_value())),
      "ARKStepSetMaxNonlinIters");
  // f_I at a solved stage follows from the stage equation: one implicit rhs less per stage.
  check_sundials(ARKStepSetDeduceImplicitRhs(mem, SUNTRUE), "ARKStepSetDeduceImplicitRhs");
}

void ArkodeStepper::set_up_linear_solver() {
  void* mem = m_arkode.get();
  // CG inside the preconditioner is not a fixed linear operator: flexible GMRES tolerates that;
  // the factorised solve is one, and plain GMRES is enough.
  const bool inexact =
      *reduced_solve_named(linear_solver_of(m_options, arkode_integrator(m_kind).named_keys)) !=
      ReducedSolve::sparse_ldlt;
  m_linear_solver.reset(detail::check_created(
      inexact ? SUNLinSol_SPFGMR(m_y_vector.get(), SUN_PREC_RIGHT, krylov_dimension, m_context)
              : SUNLinSol_SPGMR(m_y_vector.get(), SUN_PREC_RIGHT, krylov_dimension, m_context),
      "SUNLinSol_SPGMR"));
  check_linear(ARKStepSetLinearSolver(mem, m_linear_solver.get(), nullptr),
               "ARKStepSetLinearSolver");
  // Options of the linear solver interface must follow ARKStepSetLinearSolver.
  check_linear(ARKStepSetJacTimes(mem, nullptr, jacobian_times), "ARKStepSetJacTimes");
  check_linear(ARKStepSetPreconditioner(mem, preconditioner_setup, preconditioner_solve),
               "ARKStepSetPreconditioner");
}

void ArkodeStepper::restart(double initial_step) {
  void* mem = m_arkode.get();
  if (m_options.adaptive) check_sundials(ARKStepSetInitStep(mem, initial_step), "ARKStepSetInitStep");
  check_sundials(ARKStepReset(mem, m_t, m_y_vector.get()), "ARKStepReset");
  m_seen = read_counts();
}

void ArkodeStepper::record_error(int, const char*, const char*, char* message, void* self) {
  static_cast<ArkodeStepper*>(self)->m_arkode_message = message;
}

double ArkodeStepper::step(double t_stop) {
  const double start = m_t;
  if (m_options.adaptive)
    evolve(t_stop);
  else
    cover_fixed(fixed_step_end(m_options.dt, m_t, t_stop), m_options.max_step_halvings);
  m_last_step = m_t - start;
  return m_t;
}

void ArkodeStepper::evolve(double target) {
  void* mem = m_arkode.get();
  check_sundials(ARKStepSetStopTime(mem, target), "ARKStepSetStopTime");
  m_corrections = 0;
  m_arkode_message.clear();
  sunrealtype reached = m_t;
  const int flag = ARKStepEvolve(mem, target, m_y_vector.get(), &reached, ARK_ONE_STEP);
  accumulate_counters();  // a failed step's work counts too
  check_sundials(flag, "ARKStepEvolve", ARKStepGetReturnFlagName, m_arkode_message);
  const double step = reached - m_t;
  m_t = reached;
  // At the stop time ARKODE returns its interpolant, its solution to round-off: snap the fixed
  // particles again so that they are exact.
  m_system.constraints().project(m_t, positions(), velocities());
  // A penetration correction jumps the state: ARKODE's history (error estimates, stage
  // predictor) no longer describes it. The fixed-particle snap in postprocess_step moves the
  // state only by the step's own truncation error and needs no restart.
  if (m_corrections > 0) restart(step);
}

namespace {

// Failures of a step's implicit solve, which a shorter step can avoid (its predictor is closer
// to the stage solutions and its matrix closer to M).
bool solve_failed(const std::string& flag) {
  return flag == "ARK_CONV_FAILURE" || flag == "ARK_LSETUP_FAIL" || flag == "ARK_LSOLVE_FAIL";
}

}  // namespace

// A fixed step in fixed-step mode stops at its first failed solve (ARKODE does not shrink it):
// here the interval is then taken again from its start as two half steps, each of which may be
// halved again, as an adaptive code would shrink a failed step. Halvings are counted and
// reported (summary.json); every later interval starts again at the fixed step.
void ArkodeStepper::cover_fixed(double t_end, int halvings_left) {
  const double t_start = m_t;
  const Eigen::VectorXd start = m_y;
  try {
    evolve_fixed(t_end);
    return;
  } catch (const IntegratorFailure& failure) {
    if (!solve_failed(failure.flag()) || m_options.max_step_halvings == 0) throw;
    if (halvings_left == 0) {
      std::ostringstream exhausted;
      exhausted << failure.what() << " (the step was halved " << m_options.max_step_halvings
                << " times, to " << t_end - t_start << " s)";
      throw IntegratorFailure(failure.flag(), exhausted.str());
    }
  }
  ++m_counters.step_halvings;
  m_t = t_start;
  m_y = start;  // same size: the buffer that m_y_vector views
  // The failed attempt left ARKODE's history and the contact set at the failed stages.
  if (pairs_contacts()) m_system.collision().pair_contacts(positions());
  restart(t_end - t_start);
  const double middle = t_start + 0.5 * (t_end - t_start);
  cover_fixed(middle, halvings_left - 1);
  cover_fixed(t_end, halvings_left - 1);
}

// One step from m_t to exactly t_end. ARKODE only shortens a fixed step to meet the stop time,
// so the step is set to the interval each time: a remainder that fixed_step_end rounds up to a
// whole step, the halves of a halved step and the return to dt after them all land exactly.
void ArkodeStepper::evolve_fixed(double t_end) {
  check_attempts(m_options.max_steps);
  check_sundials(ARKStepSetFixedStep(m_arkode.get(), t_end - m_t), "ARKStepSetFixedStep");
  evolve(t_end);
}

ArkodeStepper::ArkodeCounts ArkodeStepper::read_counts() const {
  void* mem = m_arkode.get();
  ArkodeCounts c;
  // (ARKODE's "accsteps" are the accuracy-limited steps, not the accepted ones.)
  long stability_limited = 0, accuracy_limited = 0, nfe = 0, nfi = 0, linear_setups = 0;
  check_sundials(ARKStepGetTimestepperStats(mem, &stability_limited, &accuracy_limited,
                                            &c.attempts, &nfe, &nfi, &linear_setups,
                                            &c.error_test_failures),
                 "ARKStepGetTimestepperStats");
  check_sundials(ARKStepGetNumSteps(mem, &c.steps), "ARKStepGetNumSteps");
  c.rhs_evals = nfe + nfi;
  if (m_kind == ArkodeKind::explicit_rk) return c;
  check_sundials(ARKStepGetNonlinSolvStats(mem, &c.newton_iters, &c.newton_failures),
                 "ARKStepGetNonlinSolvStats");
  if (m_nonlinear_solver) {
    // No ARKODE linear solver: the line search's gradients and Hessians are counted here.
    c.rhs_evals += m_nonlinear_solver->rhs_evals();
    c.setups = m_nonlinear_solver->setups();
    c.backtracks = m_nonlinear_solver->backtracks();
    c.linear_iters = m_nonlinear_solver->krylov_iterations();  // CG's are added below
    return c;
  }
  check_linear(ARKStepGetNumLinIters(mem, &c.linear_iters), "ARKStepGetNumLinIters");
  check_linear(ARKStepGetNumLinConvFails(mem, &c.linear_failures), "ARKStepGetNumLinConvFails");
  check_linear(ARKStepGetNumPrecEvals(mem, &c.setups), "ARKStepGetNumPrecEvals");
  return c;
}

void ArkodeStepper::accumulate_counters() {
  const ArkodeCounts now = read_counts();
  m_counters.steps += now.steps - m_seen.steps;
  m_counters.attempts += now.attempts - m_seen.attempts;
  m_counters.rhs_evals += now.rhs_evals - m_seen.rhs_evals;
  m_counters.newton_iters += now.newton_iters - m_seen.newton_iters;
  m_counters.linear_iters += now.linear_iters - m_seen.linear_iters;
  m_counters.jacobian_setups += now.setups - m_seen.setups;
  m_counters.error_test_failures += now.error_test_failures - m_seen.error_test_failures;
  m_counters.line_search_backtracks += now.backtracks - m_seen.backtracks;
  m_counters.convergence_failures += now.newton_failures - m_seen.newton_failures +
                                     now.linear_failures - m_seen.linear_failures;
  m_seen = now;
  // CG iterations inside the preconditioner are linear iterations too.
  if (m_reduced) {
    m_counters.linear_iters += m_reduced->iterations() - m_cg_seen;
    m_cg_seen = m_reduced->iterations();
  }
}

int ArkodeStepper::explicit_rhs(sunrealtype t, N_Vector y, N_Vector y_dot, void* data) {
  ArkodeStepper& self = self_of(data);
  self.m_system.rhs(t, view(y), view(y_dot), self.m_split.explicit_part);
  return 0;
}

int ArkodeStepper::implicit_rhs(sunrealtype t, N_Vector y, N_Vector y_dot, void* data) {
  ArkodeStepper& self = self_of(data);
  self.m_system.rhs(t, view(y), view(y_dot), self.m_split.implicit_part);
  return 0;
}

int ArkodeStepper::postprocess_step(sunrealtype t, N_Vector y, void* data) {
  ArkodeStepper& self = self_of(data);
  VecMap state = view(y);
  const Eigen::Index n3 = state.size() / 2;
  self.m_corrections += self.m_system.project(t, state.head(n3), state.tail(n3));
  // ARKODE evaluates the right-hand side at the new state only after this function, so the
  // next step's first stage and the interpolant already see the new contact set.
  if (self.pairs_contacts()) self.m_system.collision().pair_contacts(state.head(n3));
  return 0;
}

int ArkodeStepper::jacobian_times(N_Vector w, N_Vector j_w, sunrealtype, N_Vector y, N_Vector,
                                  void* data, N_Vector) {
  // J w = [w_v; M^-1 (K w_x + D w_v)] with the exact (not definite) Jacobian of f_I; fixed rows
  // are zero because their right-hand side is prescribed.
  ArkodeStepper& self = self_of(data);
  const VecMap state = view(y), in = view(w);
  VecMap out = view(j_w);
  const Eigen::Index n3 = state.size() / 2;
  out.head(n3) = in.tail(n3);
  self.m_system.constraints().zero_fixed(out.head(n3));
  self.m_system.force_jacobian_times(state.head(n3), state.tail(n3), in.head(n3), in.tail(n3),
                                     out.tail(n3), false, self.m_split.implicit_part);
  out.tail(n3) /= self.m_system.particle_mass();
  return 0;
}

int ArkodeStepper::preconditioner_setup(sunrealtype, N_Vector y, N_Vector, sunbooleantype jok,
                                        sunbooleantype* jcur, sunrealtype gamma, void* data) {
  ReducedNewtonSolver& solver = *self_of(data).m_reduced;
  if (jok && solver.has_jacobian()) {
    solver.set_gamma(gamma);
    *jcur = SUNFALSE;
    return 0;
  }
  const VecMap state = view(y);
  const Eigen::Index n3 = state.size() / 2;
  solver.update(state.head(n3), state.tail(n3), gamma);
  *jcur = SUNTRUE;
  return 0;
}

int ArkodeStepper::preconditioner_solve(sunrealtype, N_Vector, N_Vector, N_Vector r, N_Vector z,
                                        sunrealtype, sunrealtype, int, void* data) {
  // An unconverged CG still returns a useful approximation: the flexible GMRES around it
  // makes up the rest. A failed factorisation is recoverable: ARKODE retries with a new setup.
  ReducedNewtonSolver& solver = *self_of(data).m_reduced;
  const bool solved = solver.solve(view(r), view(z));
  return solved || solver.method() == ReducedSolve::conjugate_gradients ? 0 : 1;
}

std::vector<IntegratorDeclaration> arkode_declarations() {
  std::vector<IntegratorDeclaration> all;
  for (const ArkodeIntegrator& a : arkode_integrators())
    all.push_back({a.name, a.family, 3, true, a.description, {},
                   [](ClothSystem& system,
                      const IntegratorOptions& options) -> std::unique_ptr<Integrator> {
                     return std::make_unique<ArkodeStepper>(system, *arkode_kind(options.name),
                                                            options);
                   },
                   a.named_keys});
  return all;
}

}  // namespace drape
