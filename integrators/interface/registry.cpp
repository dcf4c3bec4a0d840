#include "integrators/interface/registry.hpp"

#include "core/io/input_error.hpp"
#include "integrators/arkode/arkode_stepper.hpp"
#include "integrators/arkode/arkode_tables.hpp"
#include "integrators/bdf2/bdf2.hpp"
#include "integrators/implicit_euler/implicit_euler.hpp"
#include "integrators/explicit/leapfrog.hpp"
#include "integrators/newton/line_search_newton.hpp"
#include "integrators/newton/reduced_newton_solver.hpp"
#include "integrators/projective_dynamics/projective_dynamics.hpp"
#include "integrators/explicit/symplectic_euler.hpp"
#include "integrators/xpbd/xpbd.hpp"
#include "integrators/vbd/vbd.hpp"

namespace drape {

namespace {

// The ARKODE integrators, each declared once: its name, its kind of tables, and the named keys
// it reads (NamedKeys' fields in order: error_tolerances, newton_stages, linear_solves, solve,
// imex_split; the linear solver's defaults pcg-reduced and 1e-8).
struct ArkodeIntegrator {
  const char* name;
  ArkodeKind kind;
  const char* family;
  const char* description;
  NamedKeys named_keys;
};

const ArkodeIntegrator arkode_integrators[] = {
    {"arkode-erk", ArkodeKind::explicit_rk, "explicit",
     "ARKODE ARKStep explicit Runge-Kutta, any ERK table (default Bogacki-Shampine 3(2))",
     {true, false, false, false, false}},
    {"arkode-dirk", ArkodeKind::diagonally_implicit, "implicit",
     "ARKODE ARKStep diagonally implicit Runge-Kutta, any DIRK table (default TRBDF2_3_3_2)",
     {true, true, true, false, false}},
    {"arkode-imex", ArkodeKind::imex, "imex",
     "ARKODE ARKStep IMEX: springs implicit, gravity, air and collision explicit",
     {true, true, true, false, true}},
};

// The ARKODE kind of an integrator name, or nothing for our own integrators.
std::optional<ArkodeKind> arkode_kind(const std::string& name) {
  for (const ArkodeIntegrator& a : arkode_integrators)
    if (name == a.name) return a.kind;
  return std::nullopt;
}

const char* integrator_of(ArkodeKind kind) {
  for (const ArkodeIntegrator& a : arkode_integrators)
    if (a.kind == kind) return a.name;
  return "";
}

std::string names_of_kind(ArkodeKind kind) {
  std::string names;
  for (const auto& table : arkode_tables())
    if (table.kind == kind) names += (names.empty() ? "" : ", ") + table.name;
  return names;
}

std::unique_ptr<Integrator> make_arkode_stepper(ClothSystem& system,
                                                const IntegratorOptions& options) {
  return std::make_unique<ArkodeStepper>(system, *arkode_kind(options.name), options);
}

// The integrators whose keys are IntegratorOptions' named fields (docs/integrators/README.md); the
// later ones declare their own keys in their folders.
std::vector<IntegratorDeclaration> built_in_declarations() {
  std::vector<IntegratorDeclaration> all = {
      {"leapfrog", "explicit", 2, false, "the paper's leap-frog (kick-drift-kick form)", {},
       [](ClothSystem& system, const IntegratorOptions& options) -> std::unique_ptr<Integrator> {
         return std::make_unique<Leapfrog>(system, options.dt);
       },
       {},
       true},
      {"symplectic-euler", "explicit", 1, false, "semi-implicit Euler, velocity first", {},
       [](ClothSystem& system, const IntegratorOptions& options) -> std::unique_ptr<Integrator> {
         return std::make_unique<SymplecticEuler>(system, options.dt);
       },
       {},
       true},
      {"implicit-euler", "implicit", 1, false,
       "Baraff-Witkin linearised backward Euler, CG or sparse LDLT on the 3N velocity system",
       {},
       [](ClothSystem& system, const IntegratorOptions& options) -> std::unique_ptr<Integrator> {
         return std::make_unique<ImplicitEuler>(system, options);
       },
       // pcg-multigrid, measured on the draped-cloth benchmark
       // (docs/integrators/linear-solvers.md): the multigrid cycle pays for itself at
       // implicit-euler's large steps (90 -> 9 CG iterations at 1/30 s); ARKODE's adaptive steps
       // there are microseconds, S is then close to M, and block Jacobi is cheaper. 1e-3:
       // integrator_options.hpp, default_linear_tolerance.
       {false, false, true, true, false, "pcg-multigrid", 1e-3},
       true},
  };
  for (const ArkodeIntegrator& a : arkode_integrators)
    all.push_back(
        {a.name, a.family, 3, true, a.description, {}, make_arkode_stepper, a.named_keys, true});
  return all;
}

}  // namespace

const std::vector<IntegratorDeclaration>& integrators() {
  static const std::vector<IntegratorDeclaration> list = [] {
    std::vector<IntegratorDeclaration> all = built_in_declarations();
    // Each later integrator's folder declares it (integrator_declaration.hpp).
    for (IntegratorDeclaration (*declare)() : std::initializer_list<IntegratorDeclaration (*)()>{
             &xpbd_declaration, &projective_dynamics_declaration, &vbd_declaration,
             &bdf2_declaration})
      all.push_back(declare());
    return all;
  }();
  return list;
}

std::vector<TableInfo> integrator_tables() {
  std::vector<TableInfo> list;
  for (const auto& table : arkode_tables()) {
    const detail::ButcherTableHandle loaded = detail::load_main_table(table);
    list.push_back({integrator_of(table.kind), table.name, loaded->q, loaded->p, loaded->stages});
  }
  return list;
}

const IntegratorDeclaration* find_integrator(const std::string& name) {
  for (const auto& info : integrators())
    if (info.name == name) return &info;
  return nullptr;
}

void validate_integrator_choice(const IntegratorOptions& options, const std::string& file,
                                const std::string& path) {
  const std::optional<ArkodeKind> kind = arkode_kind(options.name);
  if (!kind) {
    if (!options.table.empty())
      throw InputError(file, path + ".table",
                       "integrator '" + options.name + "' takes no Butcher table");
  } else if (!options.table.empty()) {
    const ArkodeTable* table = find_arkode_table(options.table, *kind);
    if (!table)
      throw InputError(file, path + ".table",
                       "'" + options.table + "' is not a table of " + options.name +
                           " (one of: " + names_of_kind(*kind) + ")");
    if (options.adaptive && detail::load_main_table(*table)->d == nullptr)
      throw InputError(file, path + ".table",
                       "'" + options.table + "' has no embedded method: adaptive steps need one");
  }
  const IntegratorDeclaration* info = find_integrator(options.name);
  if (info && !info->named_keys.linear_solves && !options.linear_solver.empty())
    throw InputError(file, path + ".linear_solver",
                     "integrator '" + options.name + "' solves no linear system with CG or LDLT: "
                     "it takes no linear_solver");
  if (!reduced_solve_named(linear_solver_of(options)))
    throw InputError(file, path + ".linear_solver",
                     "unknown linear solver '" + options.linear_solver +
                         "' (one of: " + reduced_solve_names() + ")");
  const std::optional<ExactSolve> exact = exact_solve_named(exact_solve_of(options));
  if (!exact)
    throw InputError(file, path + ".exact_solve",
                     "unknown exact solve '" + options.exact_solve + "' (one of: " +
                         exact_solve_names() + ")");
  if (*exact == ExactSolve::bicgstab &&
      *reduced_solve_named(linear_solver_of(options)) == ReducedSolve::sparse_ldlt)
    throw InputError(file, path + ".exact_solve",
                     "bicgstab is preconditioned by the linear solver's preconditioner of S: it "
                     "needs linear_solver pcg-reduced or pcg-multigrid, not sparse-direct");
}

std::unique_ptr<Integrator> make_integrator(const IntegratorOptions& options,
                                            ClothSystem& system) {
  const IntegratorDeclaration* declaration = find_integrator(options.name);
  if (!declaration) throw std::logic_error("make_integrator: no integrator " + options.name);
  return declaration->make(system, options);
}

}  // namespace drape
