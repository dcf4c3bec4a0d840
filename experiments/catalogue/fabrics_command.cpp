#include "experiments/catalogue/fabrics_command.hpp"

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "core/fabrics/fabric.hpp"

namespace drape {

namespace {

nlohmann::json fabric_json(const Fabric& f) {
  return {{"name", f.name},
          {"kind", f.kind},
          {"source", f.source},
          {"note", f.note},
          {"areal_density", f.areal_density},
          {"tensile_stiffness", f.tensile_stiffness},
          {"shear_stiffness", f.shear_stiffness},
          {"bending_rigidity", f.bending_rigidity},
          {"units", {{"areal_density", "kg/m^2"},
                     {"tensile_stiffness", "N/m"},
                     {"shear_stiffness", "N/m"},
                     {"bending_rigidity", "N m"}}}};
}

}  // namespace

nlohmann::json fabrics_json() {
  nlohmann::json out = nlohmann::json::array();
  for (const Fabric& f : fabrics()) out.push_back(fabric_json(f));
  return out;
}

int list_fabrics(bool json) {
  if (json) {
    fmt::print("{}\n", fabrics_json().dump(2));
    return 0;
  }
  fmt::print("{:<18} {:<6} {:>10} {:>10} {:>9} {:>10}  {}\n", "fabric", "kind", "rho_A", "C11",
             "G", "B", "source");
  fmt::print("{:<18} {:<6} {:>10} {:>10} {:>9} {:>10}\n", "", "", "[kg/m^2]", "[N/m]", "[N/m]",
             "[N m]");
  for (const Fabric& f : fabrics())
    fmt::print("{:<18} {:<6} {:>10.4g} {:>10.4g} {:>9.4g} {:>10.4g}  {}\n", f.name, f.kind,
               f.areal_density, f.tensile_stiffness, f.shear_stiffness, f.bending_rigidity,
               f.source);
  fmt::print("\nscene key cloth.fabric; springs and mass per spacing: docs/fabrics.md\n");
  return 0;
}

}  // namespace drape
