#include "integrators/arkode/arkode_integrators.hpp"

#include <stdexcept>

namespace drape {

const std::vector<ArkodeIntegrator>& arkode_integrators() {
  // NamedKeys' fields in order: error_tolerances, newton_stages, linear_solves, solve,
  // imex_split; the linear solver's defaults pcg-reduced and 1e-8.
  static const std::vector<ArkodeIntegrator> list = {
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
  return list;
}

const ArkodeIntegrator& arkode_integrator(ArkodeKind kind) {
  for (const ArkodeIntegrator& a : arkode_integrators())
    if (a.kind == kind) return a;
  throw std::logic_error("arkode_integrator: no integrator of this kind");
}

std::optional<ArkodeKind> arkode_kind(const std::string& name) {
  for (const ArkodeIntegrator& a : arkode_integrators())
    if (name == a.name) return a.kind;
  return std::nullopt;
}

std::string arkode_table_names(ArkodeKind kind) {
  std::string names;
  for (const auto& table : arkode_tables())
    if (table.kind == kind) names += (names.empty() ? "" : ", ") + table.name;
  return names;
}

}  // namespace drape
