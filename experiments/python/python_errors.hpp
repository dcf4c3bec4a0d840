#pragma once
// The Python API's exceptions (docs/python.md, "Errors"): drapelab.InputError (a ValueError
// naming the file and the field) for bad input, drapelab.IntegratorFailure (a RuntimeError with
// the solver's flag) for a run that failed or diverged, OSError for a file that could not be
// written; and the translation of drapelab's C++ errors into them.
#include <pybind11/pybind11.h>

#include <stdexcept>
#include <string>

namespace drape {

/// A run that ended without reaching its end: `status` failed or diverged, `flag` the solver's
/// flag (IntegratorFailure::flag(); "diverged", "max_steps" for the loop's own ends).
class RunEndedError : public std::runtime_error {
 public:
  RunEndedError(std::string status, std::string flag, double time, const std::string& reason);
  const std::string& status() const { return m_status; }
  const std::string& flag() const { return m_flag; }
  double time() const { return m_time; }

 private:
  std::string m_status;
  std::string m_flag;
  double m_time;
};

/// Adds InputError and IntegratorFailure to `module` and translates the C++ errors into them.
void register_errors(pybind11::module_& module);

}  // namespace drape
