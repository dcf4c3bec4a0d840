#pragma once
// Solver options (the scene's `integrator` object): separate from the problem data so that a
// run is reproduced from its own output folder.
#include <nlohmann/json.hpp>
#include <string>

#include "integrators/interface/integrator_declaration.hpp"

namespace drape {

/// Which method, with which step and tolerances, and how implicit systems are solved.
struct IntegratorOptions {
  std::string name;               ///< leapfrog, symplectic-euler, implicit-euler, arkode-...
  double dt = 0.0;                ///< fixed step, or first step of an adaptive run [s]
  bool adaptive = false;          ///< error-controlled steps (ARKODE only)
  std::string table;              ///< ARKODE Butcher table name, "" for the method's default
  /// arkode-dirk: an inline Butcher table (butcher_tableau.hpp) given as `table`, null if none.
  nlohmann::json user_table;
  double rtol = 1e-4;             ///< relative tolerance of adaptive runs
  double atol = 1e-7;             ///< absolute tolerance of adaptive runs
  double max_dt = 0.0;            ///< largest adaptive step, 0 = unbounded
  /// Implicit solves (docs/integrators/linear-solvers.md), implicit integrators only; "" = the
  /// default of linear_solver_of().
  std::string linear_solver;
  /// Newton iterations per stage before a failure; 0 = max_newton_iters_of()'s default.
  int max_newton_iters = 0;
  /// arkode-dirk and arkode-imex: how stages are solved, `line-search` (Newton on the incremental
  /// potential with a line search, docs/integrators/line-search-newton.md) or `newton` (ARKODE's);
  /// "" = line-search.
  std::string nonlinear_solver;
  /// arkode-imex: which forces the implicit part f_I holds, `springs` (elastic and spring
  /// damping; the collision force explicit) or `springs+collision` (the contact implicit too);
  /// gravity and air damping stay explicit. "" = springs (docs/model.md section 5).
  std::string imex_split;
  /// implicit-euler and bdf2: `linearised` (one Newton step, Baraff and Witkin, Choi and Ko) or
  /// `converged` (the step's equation solved by the line-search Newton); "" = linearised.
  std::string solve;
  /// Runs whose stages the line-search Newton solves: how its local phase solves the exact
  /// stage Jacobian, `lu` (sparse LU) or `bicgstab` (BiCGSTAB preconditioned by the linear
  /// solver's preconditioner of S, the LU where it does not converge); "" = lu.
  std::string exact_solve;
  /// Fixed-step ARKODE runs: how many times a step whose solve fails may be halved (0: the
  /// first failure ends the run).
  int max_step_halvings = 10;
  /// Relative residual of the iterative linear solvers; 0 = the declared default
  /// (linear_tolerance_of).
  double linear_tolerance = 0.0;
  int max_linear_iters = 200;     ///< Krylov / CG iterations per solve
  long max_steps = 100000000;     ///< safety bound on steps per run
  /// The keys the integrator declares as its own (integrator_declaration.hpp), by name; a key
  /// not given holds its declared default after read_integrator_options(). Read them with the
  /// setting_* functions, which fall back to the declared default for options built in code.
  nlohmann::json settings = nlohmann::json::object();

  /// The key's value in `settings`, or the default its declaration (`declared`, the
  /// integrator's own keys, IntegratorDeclaration::keys) gives it.
  const nlohmann::json& setting(const std::string& key,
                                const std::vector<SettingKey>& declared) const;
  long setting_integer(const std::string& key, const std::vector<SettingKey>& declared) const;
  double setting_number(const std::string& key, const std::vector<SettingKey>& declared) const;
  bool setting_flag(const std::string& key, const std::vector<SettingKey>& declared) const;
  std::string setting_choice(const std::string& key,
                             const std::vector<SettingKey>& declared) const;
};

// The options as an integrator reads them, against the named keys it declares
// (integrator_declaration.hpp). registry.hpp looks the declaration up by the options' name.

/// The linear solver an implicit integrator uses: `linear_solver`, or the declared default
/// (pcg-multigrid for implicit-euler and bdf2, pcg-reduced inside ARKODE: measured,
/// docs/integrators/linear-solvers.md).
std::string linear_solver_of(const IntegratorOptions& options, const NamedKeys& declared);
/// `linear_tolerance`, or the declared default when it is 0: 1e-3 for implicit-euler and bdf2
/// (below their truncation error at any step worth taking implicitly,
/// docs/integrators/implicit-euler.md and docs/integrators/bdf2.md, "Linear tolerance"), 1e-8
/// inside ARKODE's preconditioner.
double linear_tolerance_of(const IntegratorOptions& options, const NamedKeys& declared);
/// arkode-dirk and arkode-imex: `nonlinear_solver`, or `line-search` when it is empty; "" for
/// the other integrators (which reject the key).
std::string nonlinear_solver_of(const IntegratorOptions& options, const NamedKeys& declared);
/// Whether the run solves its stages with the line-search Newton (arkode-dirk and arkode-imex
/// by default, implicit-euler and bdf2 with solve = converged).
bool uses_line_search(const IntegratorOptions& options, const NamedKeys& declared);
/// `exact_solve`, or `lu` when it is empty.
std::string exact_solve_of(const IntegratorOptions& options);
/// `max_newton_iters`, or when 0: 400 for the line-search Newton, 10 for ARKODE's Newton
/// (docs/journal/2026-11-26-iteration-bound.md).
int max_newton_iters_of(const IntegratorOptions& options, bool line_search);

}  // namespace drape
