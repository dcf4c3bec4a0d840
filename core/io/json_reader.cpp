#include "core/io/json_reader.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "core/io/json_text.hpp"

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

std::optional<std::int64_t> exact_integer(const nlohmann::json& value) {
  // Beyond 2^62 no field has a meaning, and the double comparisons below stay exact.
  constexpr double bound = 4611686018427387904.0;  // 2^62
  if (value.is_number_unsigned()) {
    const auto u = value.get<std::uint64_t>();
    if (u > static_cast<std::uint64_t>(bound)) return std::nullopt;
    return static_cast<std::int64_t>(u);
  }
  if (value.is_number_integer()) return value.get<std::int64_t>();
  if (!value.is_number_float()) return std::nullopt;
  const double x = value.get<double>();
  if (!(std::abs(x) <= bound) || std::floor(x) != x) return std::nullopt;
  return static_cast<std::int64_t>(x);
}

namespace {

// A number for a message: JSON's text where it has one, and inf, -inf or nan where JSON prints
// null (a fabric's stiffness derived from a spacing of 1e-160 read "got null").
std::string number_text(double value) {
  if (std::isfinite(value)) return nlohmann::json(value).dump();
  return std::isnan(value) ? "nan" : value > 0.0 ? "inf" : "-inf";
}

bool integral_number(const nlohmann::json& value) {
  if (value.is_number_integer()) return true;
  if (!value.is_number_float()) return false;
  const double x = value.get<double>();
  return std::isfinite(x) && std::floor(x) == x;
}

}  // namespace

int JsonReader::integer(const std::string& key) {
  const auto& value = raw(key);
  if (!integral_number(value)) throw error(key, "expected an integer, got " + quote_json(value));
  const auto wide = exact_integer(value);
  if (!wide || *wide < std::numeric_limits<int>::min() || *wide > std::numeric_limits<int>::max())
    throw error(key, "integer out of range: " + quote_json(value));
  return static_cast<int>(*wide);
}

std::int64_t JsonReader::integer_in(const std::string& key, std::int64_t low, std::int64_t high) {
  const auto& value = raw(key);
  if (!integral_number(value)) throw error(key, "expected an integer, got " + quote_json(value));
  const auto wide = exact_integer(value);
  if (!wide || *wide < low || *wide > high)
    throw error(key, "must be an integer from " + std::to_string(low) + " to " +
                         std::to_string(high) + ", got " + quote_json(value));
  return *wide;
}

std::int64_t JsonReader::integer_in(const std::string& key, std::int64_t low, std::int64_t high,
                                    std::int64_t fallback) {
  return has(key) ? integer_in(key, low, high) : fallback;
}

int JsonReader::integer(const std::string& key, int fallback) {
  return has(key) ? integer(key) : fallback;
}

bool JsonReader::boolean(const std::string& key, bool fallback) {
  if (!has(key)) return fallback;
  const auto& value = raw(key);
  if (!value.is_boolean()) throw error(key, "expected true or false, got " + quote_json(value));
  return value.get<bool>();
}

std::string JsonReader::string(const std::string& key) {
  const auto& value = raw(key);
  if (!value.is_string()) throw error(key, "expected a string, got " + quote_json(value));
  return value.get<std::string>();
}

std::string JsonReader::string(const std::string& key, const std::string& fallback) {
  return has(key) ? string(key) : fallback;
}

std::vector<double> JsonReader::numbers(const std::string& key) {
  const auto& value = raw(key);
  if (!value.is_array()) throw error(key, "expected an array of numbers, got " + quote_json(value));
  std::vector<double> out;
  out.reserve(value.size());
  for (const auto& item : value) {
    if (!item.is_number())
      throw error(key, "expected an array of numbers, got " + quote_json(value));
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
  if (!(value > 0.0)) throw error(key, "must be positive, got " + number_text(value));
  return value;
}

double JsonReader::at_most(const std::string& key, double value, double limit) const {
  if (!(value <= limit))
    throw error(key, "must be at most " + number_text(limit) + ", got " + number_text(value));
  return value;
}

double JsonReader::at_least(const std::string& key, double value, double limit) const {
  if (!(value >= limit))
    throw error(key, "must be at least " + number_text(limit) + ", got " + number_text(value));
  return value;
}

double JsonReader::within(const std::string& key, double value, double limit) const {
  within(key, Vec3(value, 0.0, 0.0), limit);
  return value;
}

Vec3 JsonReader::within(const std::string& key, const Vec3& value, double limit) const {
  if (!(value.cwiseAbs().maxCoeff() <= limit))
    throw error(key, "must be within +-" + nlohmann::json(limit).dump());
  return value;
}

double JsonReader::non_negative(const std::string& key, double value) const {
  if (!(value >= 0.0))
    throw error(key, "must not be negative, got " + number_text(value));
  return value;
}

void JsonReader::finish() const {
  for (const auto& item : m_object.items())
    if (!m_read.count(item.key())) throw error(item.key(), "unknown key");
}

std::optional<std::string> unreadable_file_reason(const std::string& file) {
  // `drapelab run ""` said "no such file", as if a file of no name had been looked for.
  if (file.empty()) return "the path is empty: name a file";
  std::error_code ec;
  const auto status = std::filesystem::status(file, ec);
  // A symbolic link loop or a path through a file: the system's own words.
  if (ec && ec != std::errc::no_such_file_or_directory) return ec.message();
  if (!std::filesystem::exists(status)) return "no such file";
  if (std::filesystem::is_directory(status)) return "is a directory, not a file";
  // A device or a pipe (/dev/zero) never ends: reading it would hang or exhaust memory.
  if (!std::filesystem::is_regular_file(status)) return "not a regular file";
  if (!std::ifstream(file)) return "cannot open file (permissions?)";
  return std::nullopt;
}

nlohmann::json read_json_file(const std::string& file) {
  if (const auto reason = unreadable_file_reason(file)) throw InputError(file, "", *reason);
  std::ifstream in(file);
  return parse_json_stream(in, file);
}

}  // namespace drape
