// The error of a file drapelab writes (docs/outputs.md, exit status 4) and the probes that name
// an unwritable output up front instead.
#include "core/io/output_error.hpp"

#include <gtest/gtest.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <fstream>

namespace drape {
namespace {

namespace fs = std::filesystem;

fs::path fresh(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("output_error_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(OutputError, WriteFailureNamesTheFileAndErrnosReason) {
  errno = ENOSPC;
  EXPECT_STREQ(write_failure("out/energy.csv").what(),
               "cannot write out/energy.csv: No space left on device");
  errno = 0;
  EXPECT_STREQ(write_failure("out/energy.csv").what(), "cannot write out/energy.csv");
}

TEST(OutputError, FailWriteRemovesTheHalfFileAndThrows) {
  const fs::path file = fresh("partial") / "half.csv";
  std::ofstream(file) << "a,b\n1,";
  errno = EDQUOT;
  try {
    fail_write(file.string());
    FAIL() << "no error";
  } catch (const OutputError& e) {
    EXPECT_EQ(std::string(e.what()), "cannot write " + file.string() + ": " + std::strerror(EDQUOT));
  }
  EXPECT_FALSE(fs::exists(file));
  remove_partial_file("/dev/null");  // a device is no half file
  EXPECT_TRUE(fs::exists("/dev/null"));
}

TEST(OutputError, UnwritableFileReasonRefusesEmptyPathsPipesAndSockets) {
  const fs::path dir = fresh("kinds");
  EXPECT_EQ(unwritable_file_reason(""), "is empty: name the file to write");
  EXPECT_EQ(unwritable_file_reason((dir / "new.csv").string()), std::nullopt) << "not there yet";
  std::ofstream(dir / "old.csv") << "x";
  EXPECT_EQ(unwritable_file_reason((dir / "old.csv").string()), std::nullopt);
  EXPECT_EQ(unwritable_file_reason("/dev/null"), std::nullopt);
  const fs::path fifo = dir / "pipe";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_EQ(unwritable_file_reason(fifo.string()), "is a named pipe or socket, not a file to write");
  const fs::path socket_path = dir / "sock";
  const int fd = socket(AF_UNIX, SOCK_STREAM, 0);
  ASSERT_GE(fd, 0);
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  ASSERT_LT(socket_path.string().size(), sizeof(address.sun_path));
  std::strcpy(address.sun_path, socket_path.c_str());
  ASSERT_EQ(bind(fd, reinterpret_cast<const sockaddr*>(&address), sizeof(address)), 0);
  EXPECT_EQ(unwritable_file_reason(socket_path.string()),
            "is a named pipe or socket, not a file to write");
  close(fd);
}

TEST(OutputError, OpenForWritingReasonProbesWithoutLeavingAFile) {
  const fs::path dir = fresh("probe");
  EXPECT_EQ(open_for_writing_reason((dir / "new.csv").string()), std::nullopt);
  EXPECT_FALSE(fs::exists(dir / "new.csv")) << "the probe removes the file it created";
  std::ofstream(dir / "kept.csv") << "content";
  EXPECT_EQ(open_for_writing_reason((dir / "kept.csv").string()), std::nullopt);
  std::ifstream kept(dir / "kept.csv");
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(kept), {}), "content") << "unchanged";
  EXPECT_EQ(open_for_writing_reason((dir / "no" / "such" / "folder.csv").string()),
            "cannot be written: No such file or directory");
  EXPECT_EQ(open_for_writing_reason(dir.string()), "cannot be written: Is a directory");
}

}  // namespace
}  // namespace drape
