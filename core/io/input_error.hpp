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

/// `text` with its control characters and the bytes of no valid UTF-8 sequence written as \xNN:
/// a message quotes input, and a NUL in a key ended the C string what() returns (the rest of the
/// message was lost), while other control bytes and binary garbage (a sensor line) reached the
/// terminal, and the reader of the log, as they were.
inline std::string printable(const std::string& text) {
  static const char* const hex = "0123456789abcdef";
  const auto byte = [&text](std::size_t i) { return static_cast<unsigned char>(text[i]); };
  // The length of the valid UTF-8 sequence at i (1 to 4), or 0 (RFC 3629's ranges, simplified:
  // a lead byte and continuation bytes 0x80-0xBF).
  const auto sequence = [&](std::size_t i) -> std::size_t {
    const unsigned char b = byte(i);
    const std::size_t n = b < 0x80 ? 1 : b >= 0xC2 && b <= 0xDF ? 2 : b >= 0xE0 && b <= 0xEF ? 3
                        : b >= 0xF0 && b <= 0xF4 ? 4 : 0;
    if (n == 0 || i + n > text.size()) return 0;
    for (std::size_t k = 1; k < n; ++k)
      if (byte(i + k) < 0x80 || byte(i + k) > 0xBF) return 0;
    return n;
  };
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t n = sequence(i);
    if (n > 1 || (n == 1 && byte(i) >= 0x20 && byte(i) != 0x7f)) {
      out.append(text, i, n);
      i += n;
    } else {
      out += "\\x";
      out += hex[byte(i) >> 4];
      out += hex[byte(i) & 0xf];
      ++i;
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
