#pragma once
// What an integrator is, said once: its name, family, order, the keys it reads beyond `name` and
// `dt` (with defaults and ranges), and its factory. The options reader, `drapelab integrators`,
// the registry and the analysis' styles ask this declaration instead of matching names
// (docs/integrators.md, "Adding an integrator").
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

/// An integrator's declaration.
struct IntegratorDeclaration {
  std::string name;         ///< the `integrator.name` that selects it
  std::string family;       ///< explicit, implicit, imex, position-based or optimisation
  int order = 1;            ///< order of accuracy of its default method
  bool adaptive = false;    ///< supports error-controlled steps
  std::string description;  ///< one line, with its citation
  std::vector<SettingKey> keys;  ///< its own keys, read into IntegratorOptions::settings
  IntegratorFactory make = nullptr;

  const SettingKey* key(const std::string& name) const;
  nlohmann::json to_json() const;
};

}  // namespace drape
