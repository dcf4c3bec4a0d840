#pragma once
// The error of a file drapelab writes (docs/outputs.md): not bad input, exit status 4.
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
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

/// Removes what a failed write left of `file`, so that no half file looks like a whole one; only
/// a regular file (a failed write to /dev/full must not remove the device).
inline void remove_partial_file(const std::string& file) {
  std::error_code ignored;
  if (std::filesystem::is_regular_file(file, ignored)) std::filesystem::remove(file, ignored);
}

/// A writer's one call once its stream has failed: the write_failure of `file` (errno read
/// first), thrown after removing what the write left of it.
[[noreturn]] inline void fail_write(const std::string& file) {
  const OutputError error = write_failure(file);
  remove_partial_file(file);
  throw error;
}

/// Why `file` cannot be the file a command writes, or nothing: an empty path, or a named pipe
/// or socket, whose opening would wait for a reader for ever (a device such as /dev/null is
/// written like a file). A folder is for the caller to name, as it says what it expected.
inline std::optional<std::string> unwritable_file_reason(const std::string& file) {
  if (file.empty()) return "is empty: name the file to write";
  std::error_code ec;
  const auto status = std::filesystem::status(file, ec);
  if (ec && ec != std::errc::no_such_file_or_directory) return ec.message();
  if (std::filesystem::is_fifo(status) || std::filesystem::is_socket(status))
    return "is a named pipe or socket, not a file to write";
  return std::nullopt;
}

/// Why `file` cannot be opened for writing, or nothing: tried by opening it for appending,
/// which changes nothing, and removing it again when it did not exist, since permissions do not
/// tell everything (root, /proc, read-only mounts). Checked before any work, a place that cannot
/// be written is bad input named up front (exit 2), not a failed write at the end (exit 4).
inline std::optional<std::string> open_for_writing_reason(const std::string& file) {
  std::error_code ec;
  const bool existed = std::filesystem::exists(std::filesystem::symlink_status(file, ec));
  std::ofstream probe(file, std::ios::app);
  const int error = errno;
  if (!probe) return std::string("cannot be written: ") + std::strerror(error);
  probe.close();
  if (!existed) std::filesystem::remove(file, ec);
  return std::nullopt;
}

}  // namespace drape
