#pragma once
#include <cstddef>
#include <stdexcept>
#include <string>

namespace drape {

/// `text` cut to at most `limit` characters, the last three "...": input can hold megabytes
/// where a message expects a word (docs/scene.md, Limits).
inline std::string shorten(const std::string& text, std::size_t limit = 200) {
  return text.size() <= limit ? text : text.substr(0, limit - 3) + "...";
}

/// `text` with its control characters written as \xNN: a message quotes input, and a NUL in a
/// key ended the C string what() returns (the rest of the message was lost) while other
/// control bytes reached the terminal as they were.
inline std::string printable(const std::string& text) {
  static const char* const hex = "0123456789abcdef";
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte >= 0x20 && byte != 0x7f) {
      out += c;
    } else {
      out += "\\x";
      out += hex[byte >> 4];
      out += hex[byte & 0xf];
    }
  }
  return out;
}

/// Bad input found at setup: names the file and the field (full dotted path) or line.
class InputError : public std::runtime_error {
 public:
  InputError(std::string file, std::string field, const std::string& message)
      : std::runtime_error(format(file, field, message)),
        m_file(std::move(file)),
        m_field(shorten(field)),
        m_message(shorten(message, 1000)) {}

  const std::string& file() const { return m_file; }
  const std::string& field() const { return m_field; }
  /// What is wrong, without the file and the field (to name another origin of the value).
  const std::string& message() const { return m_message; }

 private:
  static std::string format(const std::string& file, const std::string& field,
                            const std::string& message) {
    std::string where = file.empty() ? std::string("<input>") : file;
    if (!field.empty()) where += ": " + shorten(field);
    return printable(where + ": " + shorten(message, 1000));
  }
  std::string m_file;
  std::string m_field;
  std::string m_message;
};

}  // namespace drape
