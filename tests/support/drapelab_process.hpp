#pragma once
// Runs the drapelab executable as a user would and keeps its exit status, stdout and stderr.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace drape::testing {

struct DrapelabResult {
  int exit_code;
  std::string out;
  std::string err;
};

inline std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// `drapelab ARGS` (ARGS as a shell would split them), stdout and stderr into files named after
/// the running test, so that tests in parallel processes never share them.
inline DrapelabResult run_drapelab(const std::string& args) {
  const std::filesystem::path stem =
      std::filesystem::path(::testing::TempDir()) /
      ::testing::UnitTest::GetInstance()->current_test_info()->name();
  const std::string out = stem.string() + "_stdout.txt", err = stem.string() + "_stderr.txt";
  const std::string cmd = std::string(DRAPELAB_EXE) + " " + args + " > " + out + " 2> " + err;
  const int status = std::system(cmd.c_str());
  return {WEXITSTATUS(status), read_text(out), read_text(err)};
}

}  // namespace drape::testing
