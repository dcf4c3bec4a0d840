#pragma once
// What every fuzz target shares (docs/fuzzing.md): the input as a file, since drapelab's readers
// take paths, and the rule that bad input may throw but nothing else may go wrong.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

namespace drape::fuzz {

/// Writes the fuzzer's bytes to `name` in a directory of this process's own (nothing else in
/// it, so relative paths inside the input resolve to nothing) and returns its path.
/// The directory is removed when the fuzzer exits (each CI run left five behind in /tmp).
inline std::string input_file(const std::uint8_t* data, std::size_t size, const std::string& name) {
  struct OwnDirectory {
    std::filesystem::path path = std::filesystem::temp_directory_path() /
                                 ("drapelab_fuzz_" + std::to_string(::getpid()));
    OwnDirectory() { std::filesystem::create_directories(path); }
    ~OwnDirectory() {
      std::error_code ignored;
      std::filesystem::remove_all(path, ignored);
    }
  };
  static const OwnDirectory dir;
  const std::filesystem::path file = dir.path / name;
  std::ofstream(file, std::ios::binary).write(reinterpret_cast<const char*>(data),
                                              static_cast<std::streamsize>(size));
  return file.string();
}

/// Runs `read`; a thrown std::exception (InputError above all) is the right answer to bad
/// input. Crashes, sanitizer reports, leaks and hangs are what the fuzzer looks for.
template <class F>
int accept_input_errors(F&& read) {
  try {
    read();
  } catch (const std::exception&) {
  }
  return 0;
}

}  // namespace drape::fuzz
