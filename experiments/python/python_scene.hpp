#pragma once
// drapelab.load_scene and drapelab.Scene (docs/python.md): the scene reader of `drapelab run`,
// with --set's overrides given as a dict {"key.path": value}.
#include <pybind11/pybind11.h>

namespace drape {

/// Adds Scene and load_scene to `module`.
void bind_scene(pybind11::module_& module);

}  // namespace drape
