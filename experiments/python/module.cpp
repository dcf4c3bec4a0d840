// _drapelab: the compiled part of `import drapelab` (docs/python.md); analysis/drapelab/ is the
// package around it.
#include <pybind11/pybind11.h>

#include "experiments/catalogue/fabrics_command.hpp"
#include "experiments/python/python_errors.hpp"
#include "experiments/python/python_json.hpp"
#include "experiments/python/python_scene.hpp"
#include "experiments/python/python_simulation.hpp"
#include "experiments/output/provenance.hpp"
#include "integrators/registry/registry.hpp"

namespace py = pybind11;

PYBIND11_MODULE(_drapelab, module) {
  module.doc() = "drapelab's C++ core for Python; import drapelab instead (docs/python.md).";
  drape::register_errors(module);
  drape::bind_scene(module);
  drape::bind_simulation(module);
  module.def(
      "integrators",
      [] {
        nlohmann::json list = nlohmann::json::array();
        for (const drape::IntegratorDeclaration& d : drape::integrators()) list.push_back(d.to_json());
        return drape::python_of(list);
      },
      "Every integrator's declaration: name, family, order, adaptive, description, keys.");
  module.def(
      "tables",
      [] {
        nlohmann::json list = nlohmann::json::array();
        for (const drape::TableInfo& t : drape::integrator_tables())
          list.push_back({{"integrator", t.integrator},
                          {"name", t.name},
                          {"order", t.order},
                          {"embedded_order", t.embedded_order},
                          {"stages", t.stages}});
        return drape::python_of(list);
      },
      "Every ARKODE table integrator.table accepts, with its orders and stages.");
  module.def(
      "fabrics", [] { return drape::python_of(drape::fabrics_json()); },
      "Every fabric preset with its published source (docs/fabrics.md).");
  module.def(
      "version", [] { return drape::version_text(); },
      "Version, git commit, build type, SUNDIALS and machine, as drapelab --version prints.");
  module.attr("DRAPELAB_EXECUTABLE") = DRAPELAB_EXECUTABLE;
}
