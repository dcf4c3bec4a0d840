#pragma once
// Strict reading of one JSON object: every key read is recorded, and finish() rejects the keys
// nobody asked for. Errors name the file and the field by its full dotted path.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "core/io/input_error.hpp"
#include "core/state/state.hpp"

namespace drape {

/// Reads the fields of one JSON object, checking types, ranges and unknown keys.
class JsonReader {
 public:
  /// `path` is the dotted path of `object` inside `file` ("" for the root).
  JsonReader(const nlohmann::json& object, std::string file, std::string path);

  /// Full dotted path of a key of this object.
  std::string field(const std::string& key) const;
  const std::string& file() const { return m_file; }
  bool has(const std::string& key) const;
  /// The raw value (marks the key as read); throws when absent.
  const nlohmann::json& raw(const std::string& key);
  /// Reader for a nested object (marks the key as read); throws when absent or not an object.
  JsonReader object(const std::string& key);

  double number(const std::string& key);
  double number(const std::string& key, double fallback);
  int integer(const std::string& key);
  int integer(const std::string& key, int fallback);
  /// A 64-bit integer in [low, high]: a JSON integer, or a number with an integral value (1e8);
  /// 0.5, 1e300 and 4294967296 for a 32-bit field are errors naming the field.
  std::int64_t integer_in(const std::string& key, std::int64_t low, std::int64_t high);
  std::int64_t integer_in(const std::string& key, std::int64_t low, std::int64_t high,
                          std::int64_t fallback);
  bool boolean(const std::string& key, bool fallback);
  std::string string(const std::string& key);
  std::string string(const std::string& key, const std::string& fallback);
  Vec3 vec3(const std::string& key);
  Vec3 vec3(const std::string& key, const Vec3& fallback);
  std::vector<double> numbers(const std::string& key);

  /// Range checks that throw with the field's path.
  double positive(const std::string& key, double value) const;
  double non_negative(const std::string& key, double value) const;
  /// `value` must not exceed `limit` (docs/scene.md, Limits: products of larger values overflow).
  double at_most(const std::string& key, double value, double limit) const;
  /// `value` must be at least `limit`.
  double at_least(const std::string& key, double value, double limit) const;
  /// Every coordinate of `value` within [-limit, limit].
  double within(const std::string& key, double value, double limit) const;
  Vec3 within(const std::string& key, const Vec3& value, double limit) const;

  /// An InputError about a key of this object.
  InputError error(const std::string& key, const std::string& message) const;
  /// Throws for every key present but never read.
  void finish() const;

 private:
  const nlohmann::json& m_object;
  std::string m_file;
  std::string m_path;
  std::set<std::string> m_read;
};

/// The integer `value` holds (a JSON integer or an integral number within +-2^62), if any.
std::optional<std::int64_t> exact_integer(const nlohmann::json& value);

/// Reads a JSON file; a missing, unreadable (a directory, /dev/zero), unparsable or too deeply
/// nested file is an InputError naming it.
nlohmann::json read_json_file(const std::string& file);
/// The InputError for a path that is not a readable regular file, if it is not one.
std::optional<std::string> unreadable_file_reason(const std::string& file);

}  // namespace drape
