#include "experiments/python/python_scene.hpp"

#include <memory>
#include <string>
#include <vector>

#include "core/io/input_error.hpp"
#include "core/scene/scene.hpp"
#include "experiments/python/python_json.hpp"
#include "experiments/run/scene_simulation.hpp"

namespace py = pybind11;

namespace drape {

namespace {

// A dict of overrides as the --set arguments the command line would give: each value's JSON
// text after its key path, so that apply_override reads it back as the same value.
struct Overrides {
  std::vector<std::string> keys;
  std::vector<std::string> assignments;
};

Overrides overrides_of(py::handle overrides) {
  Overrides out;
  if (overrides.is_none()) return out;
  if (!PyDict_Check(overrides.ptr()))
    throw InputError("overrides", "", "expected a dict {\"key.path\": value}");
  for (const auto& [key, value] : overrides.cast<py::dict>()) {
    if (!PyUnicode_Check(key.ptr()))
      throw InputError("overrides", shorten(py::repr(key).cast<std::string>()),
                       "a key path must be a string such as \"integrator.dt\"");
    const std::string path = json_of(key, "overrides", "").get<std::string>();
    const std::string origin = "overrides['" + shorten(path) + "']";
    out.keys.push_back(path);
    out.assignments.push_back(path + "=" + json_of(value, origin, "").dump());
  }
  return out;
}

// Reads the scene with `use`; an error in a value an override gave names that override, as
// the command line names its --set argument (with_command_line_overrides, scene.hpp).
// The integrator's options are checked here too, not first when a Simulation is built: the
// command line's errors in a --set value of the integrator name that --set (scene.hpp).
template <class Read>
std::shared_ptr<Scene> read_with(const std::string& file, const Overrides& overrides, Read read) {
  try {
    auto scene = std::make_shared<Scene>(read(overrides.assignments));
    checked_integrator_options(*scene);
    return scene;
  } catch (const InputError& e) {
    std::optional<std::size_t> k;
    if (e.file() == "--set") {
      for (std::size_t i = 0; i < overrides.keys.size() && !k; ++i)
        if (overrides.keys[i] == e.field() || overrides.assignments[i] == e.field()) k = i;
    } else if (e.file() == file) {
      k = override_behind(overrides.assignments, e.field());
    }
    if (!k) throw;
    throw InputError("overrides['" + shorten(overrides.keys[*k]) + "']", e.field(), e.message());
  }
}

std::string path_text(py::handle path, const std::string& what) {
  const py::object text = py::module_::import("os").attr("fspath")(path);
  if (!PyUnicode_Check(text.ptr())) throw InputError(what, "path", "expected a str path");
  return json_of(text, what, "path").get<std::string>();
}

std::shared_ptr<Scene> scene_from_dict(py::handle source, py::handle overrides, py::handle base_dir) {
  const std::string file = "Scene.from_dict";
  const Overrides o = overrides_of(overrides);
  nlohmann::json json = json_of(source, file, "");
  const std::filesystem::path base =
      base_dir.is_none() ? std::filesystem::current_path() : std::filesystem::path(path_text(base_dir, file));
  return read_with(file, o, [&](const std::vector<std::string>& assignments) {
    if (!json.is_object()) throw InputError(file, "", "expected a dict");
    for (const std::string& a : assignments) apply_override(json, a);
    return parse_scene(json, file, base);
  });
}

}  // namespace

void bind_scene(py::module_& module) {
  py::class_<Scene, std::shared_ptr<Scene>>(
      module, "Scene", "A scene read and checked as drapelab run reads it (docs/scene.md).")
      .def_static("from_dict", &scene_from_dict, py::arg("scene"), py::kw_only(),
                  py::arg("overrides") = py::none(), py::arg("base_dir") = py::none(),
                  "The scene a dict gives (a scene file's JSON); relative paths in it resolve "
                  "against base_dir (default: the working directory).")
      .def_property_readonly("file", [](const Scene& s) { return s.file; })
      .def_property_readonly("duration", [](const Scene& s) { return s.duration; })
      .def_property_readonly("description", [](const Scene& s) { return s.description; })
      .def("to_dict", [](const Scene& s) { return python_of(s.source); },
           "The scene as read, overrides applied (what summary.json records).")
      .def("__repr__", [](const Scene& s) {
        return "<drapelab.Scene " + s.file + ", " + std::to_string(s.duration) + " s>";
      });
  module.def(
      "load_scene",
      [](py::handle path, py::handle overrides) {
        const std::string file = path_text(path, "load_scene");
        const Overrides o = overrides_of(overrides);
        return read_with(file, o, [&](const std::vector<std::string>& assignments) {
          return load_scene(file, assignments);
        });
      },
      py::arg("path"), py::arg("overrides") = py::none(),
      "Reads a scene file with `drapelab run`'s reader and checks; overrides = {\"key.path\": "
      "value} as its --set key.path=value. Bad input raises InputError naming file and field.");
}

}  // namespace drape
