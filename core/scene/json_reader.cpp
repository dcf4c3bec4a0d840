#include "core/scene/json_reader.hpp"

#include <cmath>
#include <fstream>
#include <limits>

namespace drape {

JsonReader::JsonReader(const nlohmann::json& object, std::string file, std::string path)
    : m_object(object), m_file(std::move(file)), m_path(std::move(path)) {
  if (!m_object.is_object())
    throw InputError(m_file, m_path, "expected a JSON object, got " +
                                         std::string(m_object.type_name()));
}

std::string JsonReader::field(const std::string& key) const {
  return m_path.empty() ? key : m_path + "." + key;
}

bool JsonReader::has(const std::string& key) const { return m_object.contains(key); }

InputError JsonReader::error(const std::string& key, const std::string& message) const {
  return InputError(m_file, field(key), message);
}

const nlohmann::json& JsonReader::raw(const std::string& key) {
  if (!has(key)) throw error(key, "required field is missing");
  m_read.insert(key);
  return m_object.at(key);
}

JsonReader JsonReader::object(const std::string& key) {
  return JsonReader(raw(key), m_file, field(key));
}

double JsonReader::number(const std::string& key) {
  const auto& value = raw(key);
  if (!value.is_number())
    throw error(key, "expected a number, got " + std::string(value.type_name()));
  const double x = value.get<double>();
  if (!std::isfinite(x)) throw error(key, "must be finite");
  return x;
}

double JsonReader::number(const std::string& key, double fallback) {
  return has(key) ? number(key) : fallback;
}

int JsonReader::integer(const std::string& key) {
  const auto& value = raw(key);
  if (!value.is_number_integer())
    throw error(key, "expected an integer, got " + value.dump());
  const auto wide = value.get<long long>();
  if (wide < std::numeric_limits<int>::min() || wide > std::numeric_limits<int>::max())
    throw error(key, "integer out of range: " + value.dump());
  return static_cast<int>(wide);
}

int JsonReader::integer(const std::string& key, int fallback) {
  return has(key) ? integer(key) : fallback;
}

bool JsonReader::boolean(const std::string& key, bool fallback) {
  if (!has(key)) return fallback;
  const auto& value = raw(key);
  if (!value.is_boolean()) throw error(key, "expected true or false, got " + value.dump());
  return value.get<bool>();
}

std::string JsonReader::string(const std::string& key) {
  const auto& value = raw(key);
  if (!value.is_string()) throw error(key, "expected a string, got " + value.dump());
  return value.get<std::string>();
}

std::string JsonReader::string(const std::string& key, const std::string& fallback) {
  return has(key) ? string(key) : fallback;
}

std::vector<double> JsonReader::numbers(const std::string& key) {
  const auto& value = raw(key);
  if (!value.is_array()) throw error(key, "expected an array of numbers, got " + value.dump());
  std::vector<double> out;
  out.reserve(value.size());
  for (const auto& item : value) {
    if (!item.is_number()) throw error(key, "expected an array of numbers, got " + value.dump());
    out.push_back(item.get<double>());
    if (!std::isfinite(out.back())) throw error(key, "must be finite");
  }
  return out;
}

Vec3 JsonReader::vec3(const std::string& key) {
  const auto values = numbers(key);
  if (values.size() != 3) throw error(key, "expected 3 numbers [x, y, z]");
  return Vec3(values[0], values[1], values[2]);
}

Vec3 JsonReader::vec3(const std::string& key, const Vec3& fallback) {
  return has(key) ? vec3(key) : fallback;
}

double JsonReader::positive(const std::string& key, double value) const {
  if (!(value > 0.0)) throw error(key, "must be positive, got " + nlohmann::json(value).dump());
  return value;
}

double JsonReader::non_negative(const std::string& key, double value) const {
  if (!(value >= 0.0))
    throw error(key, "must not be negative, got " + nlohmann::json(value).dump());
  return value;
}

void JsonReader::finish() const {
  for (const auto& item : m_object.items())
    if (!m_read.count(item.key())) throw error(item.key(), "unknown key");
}

nlohmann::json read_json_file(const std::string& file) {
  std::ifstream in(file);
  if (!in) throw InputError(file, "", "cannot open file");
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {  // parse errors and out-of-range numbers
    throw InputError(file, "", std::string("not valid JSON: ") + e.what());
  }
}

}  // namespace drape
