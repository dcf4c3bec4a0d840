#pragma once
// What an integrator is, said once: its name, family, order, the keys it reads beyond `name` and
// `dt` (with defaults and ranges), and its factory. The options reader, `drapelab integrators`,
// the registry and the analysis' styles ask this declaration instead of matching names
// (docs/integrators/README.md, "Adding an integrator").
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace drape {

class ClothSystem;
class Integrator;
struct IntegratorOptions;

/// One key of an integrator's own, read into IntegratorOptions::settings with its default.
struct SettingKey {
  enum class Type { integer, number, boolean, choice };
  std::string name;
  Type type = Type::number;
  nlohmann::json default_value;
  double min = 0.0;  ///< integer and number: smallest value (excluded when open_min)
  double max = 0.0;  ///< integer and number: largest value (excluded when open_max)
  bool open_min = false;
  bool open_max = false;
  std::vector<std::string> choices;  ///< choice: the values it takes
  std::string description;

  static SettingKey integer(std::string name, long value, long min, long max,
                            std::string description);
  static SettingKey number(std::string name, double value, double min, double max,
                           std::string description, bool open_min = false,
                           bool open_max = false);
  static SettingKey boolean(std::string name, bool value, std::string description);
  static SettingKey choice(std::string name, std::string value, std::vector<std::string> choices,
                           std::string description);
  /// "integer in [1, 1000], default 10" and the like, for listings and error messages.
  std::string range_text() const;
};

/// Builds an integrator stepping `system` with `options` (already read and checked).
using IntegratorFactory = std::unique_ptr<Integrator> (*)(ClothSystem& system,
                                                          const IntegratorOptions& options);

/// Which of IntegratorOptions' named keys (the fields older than SettingKey, shared by several
/// integrators) an integrator reads, and the defaults it gives the linear solver's. Left out of a
/// declaration: none of them, as for the explicit integrators.
struct NamedKeys {
  bool error_tolerances = false;  ///< rtol and atol (the arkode-* integrators)
  /// max_newton_iters, nonlinear_solver and, on fixed steps, max_step_halvings: stages solved
  /// by ARKODE's Newton or the line search (arkode-dirk, arkode-imex)
  bool newton_stages = false;
  bool linear_solves = false;  ///< linear_tolerance and max_linear_iters
  /// `solve`, linearised or converged; a converged run reads rtol, atol, max_newton_iters,
  /// exact_solve and max_step_halvings too (implicit-euler, bdf2)
  bool solve = false;
  bool imex_split = false;  ///< imex_split (arkode-imex)
  std::string linear_solver = "pcg-reduced";  ///< `linear_solver` when not given
  double linear_tolerance = 1e-8;             ///< `linear_tolerance` when not given
};

/// An integrator's declaration.
struct IntegratorDeclaration {
  std::string name;         ///< the `integrator.name` that selects it
  std::string family;       ///< explicit, implicit, imex, position-based or optimisation
  int order = 1;            ///< order of accuracy of its default method
  bool adaptive = false;    ///< supports error-controlled steps
  std::string description;  ///< one line, with its citation
  std::vector<SettingKey> keys;  ///< its own keys, read into IntegratorOptions::settings
  IntegratorFactory make = nullptr;
  NamedKeys named_keys = {};  ///< the named keys it reads (not listed by to_json)

  nlohmann::json to_json() const;
};

}  // namespace drape
