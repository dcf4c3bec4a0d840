#pragma once
#include <stdexcept>
#include <string>

namespace drape {

/// Bad input found at setup: names the file and the field (full dotted path) or line.
class InputError : public std::runtime_error {
 public:
  InputError(std::string file, std::string field, const std::string& message)
      : std::runtime_error(format(file, field, message)),
        m_file(std::move(file)),
        m_field(std::move(field)) {}

  const std::string& file() const { return m_file; }
  const std::string& field() const { return m_field; }

 private:
  static std::string format(const std::string& file, const std::string& field,
                            const std::string& message) {
    std::string where = file.empty() ? std::string("<input>") : file;
    if (!field.empty()) where += ": " + field;
    return where + ": " + message;
  }
  std::string m_file;
  std::string m_field;
};

}  // namespace drape
