#include "experiments/python/python_json.hpp"

#include <cmath>

#include "core/io/input_error.hpp"
#include "core/io/json_text.hpp"

namespace py = pybind11;

namespace drape {

namespace {

std::string child(const std::string& field, const std::string& key) {
  return field.empty() ? key : field + "." + key;
}

nlohmann::json convert(py::handle value, const std::string& file, const std::string& field,
                       int depth) {
  if (depth > max_json_depth)
    throw InputError(file, field, "nested deeper than " + std::to_string(max_json_depth) + " levels");
  if (value.is_none()) return nullptr;
  if (PyBool_Check(value.ptr())) return value.cast<bool>();
  if (PyLong_Check(value.ptr())) {
    int overflow = 0;
    const long long n = PyLong_AsLongLongAndOverflow(value.ptr(), &overflow);
    if (overflow != 0) throw InputError(file, field, "an integer beyond 64 bits");
    return n;
  }
  if (PyFloat_Check(value.ptr())) {
    const double x = value.cast<double>();
    if (!std::isfinite(x)) throw InputError(file, field, "not a finite number");
    return x;
  }
  if (PyUnicode_Check(value.ptr())) {
    Py_ssize_t size = 0;
    const char* text = PyUnicode_AsUTF8AndSize(value.ptr(), &size);
    if (text == nullptr) {
      PyErr_Clear();  // a lone surrogate: no UTF-8 text
      throw InputError(file, field, "not valid UTF-8 text");
    }
    return std::string(text, static_cast<std::size_t>(size));
  }
  if (PyDict_Check(value.ptr())) {
    nlohmann::json object = nlohmann::json::object();
    for (const auto& [key, item] : value.cast<py::dict>()) {
      if (!PyUnicode_Check(key.ptr()))
        throw InputError(file, field, "a key that is not a string: " + shorten(py::repr(key).cast<std::string>()));
      const std::string name = convert(key, file, field, depth + 1).get<std::string>();
      object[name] = convert(item, file, child(field, name), depth + 1);
    }
    return object;
  }
  if (PyList_Check(value.ptr()) || PyTuple_Check(value.ptr())) {
    nlohmann::json array = nlohmann::json::array();
    std::size_t i = 0;
    for (const py::handle item : value)
      array.push_back(convert(item, file, field + "[" + std::to_string(i++) + "]", depth + 1));
    return array;
  }
  // NumPy scalars and arrays become the Python values they hold (tolist: nested lists).
  const py::module_ numpy = py::module_::import("numpy");
  if (py::isinstance(value, numpy.attr("ndarray")) || py::isinstance(value, numpy.attr("generic")))
    return convert(value.attr("tolist")(), file, field, depth);
  throw InputError(file, field,
                   "a " + shorten(py::str(value.get_type().attr("__name__")).cast<std::string>()) +
                       " is not a JSON value (dict, list, str, int, float, bool or None)");
}

}  // namespace

nlohmann::json json_of(py::handle value, const std::string& file, const std::string& field) {
  return convert(value, file, field, 0);
}

py::object python_of(const nlohmann::json& value) {
  return py::module_::import("json").attr("loads")(value.dump());
}

}  // namespace drape
