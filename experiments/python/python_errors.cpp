#include "experiments/python/python_errors.hpp"

#include <fmt/format.h>

#include "core/io/input_error.hpp"
#include "core/io/output_error.hpp"

namespace py = pybind11;

namespace drape {

namespace {

// The exception types live as long as the interpreter: owned here, never released (a type
// released at exit after the interpreter's end would be a crash).
PyObject* input_error_type = nullptr;
PyObject* integrator_failure_type = nullptr;

PyObject* new_type(py::module_& module, const char* name, PyObject* base, const char* doc) {
  const std::string qualified = std::string(py::str(module.attr("__name__"))) + "." + name;
  PyObject* type = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, base, nullptr);
  if (type == nullptr) throw py::error_already_set();
  Py_INCREF(type);
  module.add_object(name, py::handle(type));
  return type;
}

// Raises an instance of `type` with `message` and the given attributes.
template <class... Attributes>
void raise(PyObject* type, const std::string& message, const Attributes&... attributes) {
  py::object error = py::reinterpret_borrow<py::object>(type)(message);
  ((error.attr(attributes.first) = attributes.second), ...);
  PyErr_SetObject(type, error.ptr());
}

}  // namespace

RunEndedError::RunEndedError(std::string status, std::string flag, double time,
                             const std::string& reason)
    : std::runtime_error(fmt::format("the run {} at t = {:.6g} s: {}", status, time, reason)),
      m_status(std::move(status)),
      m_flag(std::move(flag)),
      m_time(time) {}

void register_errors(py::module_& module) {
  input_error_type = new_type(module, "InputError", PyExc_ValueError,
                              "Bad input: names the file (or the call) and the field.");
  integrator_failure_type =
      new_type(module, "IntegratorFailure", PyExc_RuntimeError,
               "A run that failed (a solver's flag) or diverged; the state stays as it was.");
  py::register_exception_translator([](std::exception_ptr thrown) {
    try {
      if (thrown) std::rethrow_exception(thrown);
    } catch (const InputError& e) {
      // printable(): a file name or a key need not be UTF-8, a Python str must.
      raise(input_error_type, e.what(), std::pair{"file", py::str(printable(e.file()))},
            std::pair{"field", py::str(printable(e.field()))},
            std::pair{"message", py::str(printable(e.message()))});
    } catch (const RunEndedError& e) {
      raise(integrator_failure_type, e.what(), std::pair{"flag", py::str(e.flag())},
            std::pair{"status", py::str(e.status())}, std::pair{"time", py::float_(e.time())});
    } catch (const OutputError& e) {
      PyErr_SetString(PyExc_OSError, e.what());
    }
  });
}

}  // namespace drape
