#pragma once
// drapelab.Simulation (docs/python.md): a scene stepped from Python. Long calls release the GIL
// and take Ctrl-C between steps; positions and velocities are read-only NumPy views of the
// state; no call, in any order or with any argument, may end the interpreter.
#include <pybind11/pybind11.h>

namespace drape {

/// Adds Simulation to `module`.
void bind_simulation(pybind11::module_& module);

}  // namespace drape
