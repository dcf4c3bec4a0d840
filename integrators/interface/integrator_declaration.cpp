#include "integrators/interface/integrator_declaration.hpp"

#include <fmt/format.h>

#include <cmath>

#include "core/io/json_reader.hpp"

namespace drape {

SettingKey SettingKey::integer(std::string name, long value, long min, long max,
                               std::string description) {
  SettingKey k;
  k.name = std::move(name);
  k.type = Type::integer;
  k.default_value = value;
  k.min = static_cast<double>(min);
  k.max = static_cast<double>(max);
  k.description = std::move(description);
  return k;
}

SettingKey SettingKey::number(std::string name, double value, double min, double max,
                              std::string description, bool open_min, bool open_max) {
  SettingKey k;
  k.name = std::move(name);
  k.type = Type::number;
  k.default_value = value;
  k.min = min;
  k.max = max;
  k.open_min = open_min;
  k.open_max = open_max;
  k.description = std::move(description);
  return k;
}

SettingKey SettingKey::boolean(std::string name, bool value, std::string description) {
  SettingKey k;
  k.name = std::move(name);
  k.type = Type::boolean;
  k.default_value = value;
  k.description = std::move(description);
  return k;
}

SettingKey SettingKey::choice(std::string name, std::string value,
                              std::vector<std::string> choices, std::string description) {
  SettingKey k;
  k.name = std::move(name);
  k.type = Type::choice;
  k.default_value = std::move(value);
  k.choices = std::move(choices);
  k.description = std::move(description);
  return k;
}

std::string SettingKey::range_text() const {
  switch (type) {
    case Type::integer:
      return fmt::format("integer in [{}, {}], default {}", static_cast<long>(min),
                         static_cast<long>(max), default_value.get<long>());
    case Type::number:
      return fmt::format("number in {}{:g}, {:g}{}, default {:g}", open_min ? "(" : "[", min, max,
                         open_max ? ")" : "]", default_value.get<double>());
    case Type::boolean:
      return fmt::format("true or false, default {}", default_value.get<bool>());
    case Type::choice:
      return fmt::format("one of {}, default {}", fmt::join(choices, ", "),
                         default_value.get<std::string>());
  }
  return "";
}

nlohmann::json IntegratorDeclaration::to_json() const {
  nlohmann::json listed = nlohmann::json::array();
  for (const SettingKey& k : keys)
    listed.push_back({{"name", k.name},
                      {"default", k.default_value},
                      {"range", k.range_text()},
                      {"description", k.description}});
  return {{"name", name},     {"family", family},           {"order", order},
          {"adaptive", adaptive}, {"description", description}, {"keys", listed}};
}

}  // namespace drape
