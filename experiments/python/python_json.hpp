#pragma once
// Python values <-> JSON for the Python API (docs/python.md): a scene or overrides given as
// dicts reach the scene reader as the JSON a file would give, each value checked on the way.
#include <pybind11/pybind11.h>

#include <nlohmann/json.hpp>
#include <string>

namespace drape {

/// The JSON of a Python value made of dict (str keys), list, tuple, str, int, float, bool,
/// None and NumPy scalars or arrays. Throws InputError naming `file` and the value's dotted
/// path below `field` for anything else, a non-finite number or nesting deeper than
/// max_json_depth (what a JSON file may hold, json_text.hpp).
nlohmann::json json_of(pybind11::handle value, const std::string& file, const std::string& field);
/// A JSON value as Python's json module reads it (dict, list, str, int, float, bool, None).
pybind11::object python_of(const nlohmann::json& value);

}  // namespace drape
