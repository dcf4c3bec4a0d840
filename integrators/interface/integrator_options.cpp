#include "integrators/interface/integrator_options.hpp"

#include <stdexcept>

namespace drape {

// A key the integrator does not declare is a programming error.
const nlohmann::json& IntegratorOptions::setting(const std::string& key,
                                                 const std::vector<SettingKey>& declared) const {
  if (const auto it = settings.find(key); it != settings.end()) return *it;
  for (const SettingKey& k : declared)
    if (k.name == key) return k.default_value;
  throw std::logic_error("integrator '" + name + "' declares no key " + key);
}

long IntegratorOptions::setting_integer(const std::string& key,
                                        const std::vector<SettingKey>& declared) const {
  return setting(key, declared).get<long>();
}
double IntegratorOptions::setting_number(const std::string& key,
                                         const std::vector<SettingKey>& declared) const {
  return setting(key, declared).get<double>();
}
bool IntegratorOptions::setting_flag(const std::string& key,
                                     const std::vector<SettingKey>& declared) const {
  return setting(key, declared).get<bool>();
}
std::string IntegratorOptions::setting_choice(const std::string& key,
                                              const std::vector<SettingKey>& declared) const {
  return setting(key, declared).get<std::string>();
}

std::string linear_solver_of(const IntegratorOptions& options, const NamedKeys& declared) {
  return options.linear_solver.empty() ? declared.linear_solver : options.linear_solver;
}

double linear_tolerance_of(const IntegratorOptions& options, const NamedKeys& declared) {
  return options.linear_tolerance > 0.0 ? options.linear_tolerance : declared.linear_tolerance;
}

std::string nonlinear_solver_of(const IntegratorOptions& options, const NamedKeys& declared) {
  if (!declared.newton_stages) return "";
  // The line search is the default of the two Newton integrators
  // (docs/integrators/line-search-newton.md, "Default"): ARKODE's Newton rejects the first, growing
  // iterations of a large step and has it halved. `newton` stays selectable.
  return options.nonlinear_solver.empty() ? "line-search" : options.nonlinear_solver;
}

bool uses_line_search(const IntegratorOptions& options, const NamedKeys& declared) {
  if (declared.solve) return options.solve == "converged";
  return nonlinear_solver_of(options, declared) == "line-search";
}

int max_newton_iters_of(const IntegratorOptions& options, bool line_search) {
  if (options.max_newton_iters > 0) return options.max_newton_iters;
  // 400, not 100: on the drape scene at 1/30 s every step that halved at 100 iterations
  // converged within 400 (docs/journal/2026-11-26-iteration-bound.md).
  return line_search ? 400 : 10;
}

std::string exact_solve_of(const IntegratorOptions& options) {
  return options.exact_solve.empty() ? "lu" : options.exact_solve;
}

}  // namespace drape
