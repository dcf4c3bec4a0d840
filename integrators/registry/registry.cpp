#include "integrators/registry/registry.hpp"

#include "core/io/input_error.hpp"
#include "integrators/arkode/arkode_integrators.hpp"
#include "integrators/arkode/arkode_stepper.hpp"
#include "integrators/bdf2/bdf2.hpp"
#include "integrators/explicit/leapfrog.hpp"
#include "integrators/explicit/symplectic_euler.hpp"
#include "integrators/implicit_euler/implicit_euler.hpp"
#include "integrators/newton/line_search_newton.hpp"
#include "integrators/projective_dynamics/projective_dynamics.hpp"
#include "integrators/vbd/vbd.hpp"
#include "integrators/xpbd/xpbd.hpp"

namespace drape {

namespace {

// The explicit integrators read no key beyond name and dt: their declarations are said here.
std::vector<IntegratorDeclaration> explicit_declarations() {
  return {
      {"leapfrog", "explicit", 2, false, "the paper's leap-frog (kick-drift-kick form)", {},
       [](ClothSystem& system, const IntegratorOptions& options) -> std::unique_ptr<Integrator> {
         return std::make_unique<Leapfrog>(system, options.dt);
       }},
      {"symplectic-euler", "explicit", 1, false, "semi-implicit Euler, velocity first", {},
       [](ClothSystem& system, const IntegratorOptions& options) -> std::unique_ptr<Integrator> {
         return std::make_unique<SymplecticEuler>(system, options.dt);
       }},
  };
}

}  // namespace

const std::vector<IntegratorDeclaration>& integrators() {
  static const std::vector<IntegratorDeclaration> list = [] {
    // Each integrator's folder declares it (integrator_declaration.hpp).
    std::vector<IntegratorDeclaration> all = explicit_declarations();
    all.push_back(implicit_euler_declaration());
    for (IntegratorDeclaration& arkode : arkode_declarations()) all.push_back(std::move(arkode));
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
    list.push_back(
        {arkode_integrator(table.kind).name, table.name, loaded->q, loaded->p, loaded->stages});
  }
  return list;
}

const IntegratorDeclaration* find_integrator(const std::string& name) {
  for (const auto& info : integrators())
    if (info.name == name) return &info;
  return nullptr;
}

const NamedKeys& named_keys_of(const std::string& name) {
  static const NamedKeys none;
  const IntegratorDeclaration* declaration = find_integrator(name);
  return declaration ? declaration->named_keys : none;
}

std::string linear_solver_of(const IntegratorOptions& options) {
  return linear_solver_of(options, named_keys_of(options.name));
}

double linear_tolerance_of(const IntegratorOptions& options) {
  return linear_tolerance_of(options, named_keys_of(options.name));
}

std::string nonlinear_solver_of(const IntegratorOptions& options) {
  return nonlinear_solver_of(options, named_keys_of(options.name));
}

bool uses_line_search(const IntegratorOptions& options) {
  return uses_line_search(options, named_keys_of(options.name));
}

int max_newton_iters_of(const IntegratorOptions& options) {
  return max_newton_iters_of(options, uses_line_search(options));
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
                           " (one of: " + arkode_table_names(*kind) + ")");
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
