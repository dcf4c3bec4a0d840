#include "integrators/registry.hpp"

#include "core/input_error.hpp"
#include "integrators/leapfrog.hpp"
#include "integrators/symplectic_euler.hpp"

namespace drape {

const std::vector<IntegratorInfo>& integrators() {
  static const std::vector<IntegratorInfo> list = {
      {"leapfrog", "explicit", 2, false, "the paper's leap-frog (kick-drift-kick form)"},
      {"symplectic-euler", "explicit", 1, false, "semi-implicit Euler, velocity first"},
  };
  return list;
}

std::vector<TableInfo> integrator_tables() { return {}; }

const IntegratorInfo* find_integrator(const std::string& name) {
  for (const auto& info : integrators())
    if (info.name == name) return &info;
  return nullptr;
}

void validate_integrator_choice(const IntegratorOptions& options, const std::string& file,
                                const std::string& path) {
  if (!options.table.empty())
    throw InputError(file, path + ".table",
                     "integrator '" + options.name + "' takes no Butcher table");
}

std::unique_ptr<Integrator> make_integrator(const IntegratorOptions& options,
                                            ClothSystem& system) {
  if (options.name == "leapfrog") return std::make_unique<Leapfrog>(system, options.dt);
  if (options.name == "symplectic-euler")
    return std::make_unique<SymplecticEuler>(system, options.dt);
  throw std::logic_error("make_integrator: no factory for " + options.name);
}

}  // namespace drape
