#pragma once
// The error of a file drapelab writes (docs/outputs.md): not bad input, exit status 4.
#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>

namespace drape {

/// A file that could not be written (a full disk, a quota, a file size limit, no permission):
/// the command stops at the first failed write with exit status 4.
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// "cannot write FILE: REASON", the reason from errno as the failed write left it.
inline OutputError write_failure(const std::string& file) {
  const int error = errno;  // read before anything else can change it
  return OutputError("cannot write " + file +
                     (error != 0 ? std::string(": ") + std::strerror(error) : std::string()));
}

}  // namespace drape
