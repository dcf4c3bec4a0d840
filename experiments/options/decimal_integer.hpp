#pragma once
// CLI11 2.1 reads integer options with strtoll(..., base 0), so `--port 0x50` meant port 80 and
// `-j 010` meant 8 jobs. Integer options of drapelab are decimal (docs/model.md section 9, the
// command line): this transform (Option::transform; check() would not let it change the text)
// runs on the text before CLI11 converts it, refuses anything but digits and drops leading
// zeros, which base 0 would read as octal.
#include <CLI/Error.hpp>  // Validators.hpp uses ValidationError without including it (CLI11 2.1)
#include <CLI/Validators.hpp>

#include <string>

namespace drape {

/// A validator accepting only an optional sign followed by decimal digits, e.g. "8080", "-1",
/// "010" (read as 10).
inline CLI::Validator decimal_integer() {
  return CLI::Validator(
      [](std::string& text) {
        std::size_t i = (!text.empty() && (text[0] == '+' || text[0] == '-')) ? 1 : 0;
        if (i == text.size()) return std::string("expected a decimal integer, got '" + text + "'");
        for (; i < text.size(); ++i) {
          if (text[i] < '0' || text[i] > '9') {
            return std::string("expected a decimal integer, got '" + text + "'");
          }
        }
        const std::size_t sign = (text[0] == '+' || text[0] == '-') ? 1 : 0;
        const std::size_t first_nonzero = text.find_first_not_of('0', sign);
        text.erase(sign, (first_nonzero == std::string::npos ? text.size() - 1 : first_nonzero) - sign);
        return std::string();
      },
      "INT");
}

}  // namespace drape
