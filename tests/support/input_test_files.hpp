#pragma once
// Files for the hand-input tests: a fresh directory per test, small synthetic files written
// into it, the real Kinect recordings, and a check that bad input names file and line/field.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <string>
#include <system_error>
#include <vector>

#include "core/io/input_error.hpp"

namespace drape::test {

/// The directories test_dir() made, removed when the test program exits (each ctest run left
/// its fifteen behind in /tmp, named by process id).
struct TestDirs {
  std::vector<std::filesystem::path> made;
  ~TestDirs() {
    for (const auto& dir : made) {
      std::error_code ignored;
      std::filesystem::remove_all(dir, ignored);
    }
  }
};

inline TestDirs& test_dirs() {
  static TestDirs dirs;
  return dirs;
}

/// A fresh empty directory for the current test (unique per test and process), removed at exit.
inline std::filesystem::path test_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const auto dir = std::filesystem::temp_directory_path() /
                   ("drapelab_input_" + std::string(info->test_suite_name()) + "_" +
                    info->name() + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  test_dirs().made.push_back(dir);
  return dir;
}

/// Writes `text` to `dir/name` and returns the file's path.
inline std::string write_file(const std::filesystem::path& dir, const std::string& name,
                              const std::string& text) {
  const auto path = dir / name;
  std::ofstream(path) << text;
  return path.string();
}

/// Path of one of the real Kinect v2 recordings shipped with the project.
inline std::string kinect_recording(const std::string& name) {
  return std::string(DRAPE_SOURCE_DIR) + "/experiments/recordings/kinect-v2/" + name;
}

/// Asserts that `f` throws an InputError whose message contains every one of `parts`.
template <class F>
void expect_input_error(F&& f, std::initializer_list<std::string> parts) {
  try {
    f();
    ADD_FAILURE() << "expected an InputError";
  } catch (const InputError& e) {
    for (const auto& part : parts)
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos)
          << "message \"" << e.what() << "\" lacks \"" << part << "\"";
  }
}

}  // namespace drape::test
