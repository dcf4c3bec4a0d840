#pragma once
// The three ARKODE integrators, each said once: its name, its kind of tables and the named keys
// it reads (integrator_declaration.hpp). The stepper reads its defaults here; the registry its
// names and kinds.
#include <optional>
#include <string>
#include <vector>

#include "integrators/arkode/arkode_tables.hpp"
#include "integrators/interface/integrator_declaration.hpp"

namespace drape {

/// One ARKODE integrator.
struct ArkodeIntegrator {
  const char* name;
  ArkodeKind kind;
  const char* family;
  const char* description;
  NamedKeys named_keys;
};

/// arkode-erk, arkode-dirk and arkode-imex, in the order `drapelab integrators` lists them.
const std::vector<ArkodeIntegrator>& arkode_integrators();
/// The ARKODE integrator of kind `kind`.
const ArkodeIntegrator& arkode_integrator(ArkodeKind kind);
/// The ARKODE kind of an integrator name, or nothing for the other integrators.
std::optional<ArkodeKind> arkode_kind(const std::string& name);
/// The names of the tables of kind `kind`, comma-separated (for error messages).
std::string arkode_table_names(ArkodeKind kind);

}  // namespace drape
