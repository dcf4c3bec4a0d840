// `drapelab convert`: frames, duration and dropped frames of a recording.
#include "experiments/cli/convert_command.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include <sys/stat.h>
#include <sys/wait.h>

#include "tests/support/drapelab_process.hpp"

namespace {

drape::Recording at_times(const std::vector<double>& times) {
  drape::Recording r;
  for (const double t : times) r.frames.push_back({t, std::nullopt, std::nullopt, {}});
  return r;
}

TEST(ConvertCommand, CountsFramesLostInGapsOfTheMedianInterval) {
  // 30 fps with one frame missing after 0.1 and two after 0.2 (0.1333..., 0.3 absent).
  const double f = 1.0 / 30.0;
  const auto s = drape::recording_stats(
      at_times({0.0, f, 2 * f, 3 * f, 5 * f, 6 * f, 9 * f, 10 * f, 11 * f}));
  EXPECT_EQ(s.frames, 9);
  EXPECT_DOUBLE_EQ(s.duration, 11 * f);
  EXPECT_DOUBLE_EQ(s.frame_interval, f);
  EXPECT_EQ(s.dropped, 1 + 2);
  EXPECT_EQ(drape::recording_stats(at_times({0.5})).dropped, 0);
  EXPECT_EQ(drape::recording_stats(at_times({})).frames, 0);
}

TEST(ConvertCommand, PrintsFramesDurationAndDroppedFrames) {
  const std::string in = std::string(DRAPE_SOURCE_DIR) +
                         "/experiments/recordings/kinect-v2/Ges03_drawlines.csv";
  const std::string out = ::testing::TempDir() + "/ges03.jsonl";
  const auto r = drape::testing::run_drapelab("convert " + in + " " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto stats = drape::recording_stats(drape::read_recording(out));
  EXPECT_GT(stats.frames, 10);
  char expected[64];
  std::snprintf(expected, sizeof expected, "%d frames, %.3f s", stats.frames, stats.duration);
  EXPECT_NE(r.out.find(expected), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(std::to_string(stats.dropped) + " dropped frames"), std::string::npos)
      << r.out;
}

TEST(ConvertCommand, RefusesItsInputAsOutputAFolderOrADeviceAndAFailedWriteIsExit4) {
  const std::string dir = ::testing::TempDir() + "/convert_refused";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string in = dir + "/ges03.csv";
  std::filesystem::copy_file(std::string(DRAPE_SOURCE_DIR) +
                                 "/experiments/recordings/kinect-v2/Ges03_drawlines.csv", in);
  const std::string source = drape::testing::read_text(in);
  auto expect_error = [](const std::string& args, int code, const std::string& message) {
    const auto r = drape::testing::run_drapelab("convert " + args);
    EXPECT_EQ(r.exit_code, code) << args << ": " << r.err;
    EXPECT_EQ(r.err, "drapelab: error: " + message + "\n") << args;
  };
  // The same file by another name: nothing written, the source intact.
  expect_error(in + " " + dir + "/../convert_refused/ges03.csv", 2,
               dir + "/../convert_refused/ges03.csv: is the input recording " + in +
                   ": converting would overwrite it");
  EXPECT_EQ(drape::testing::read_text(in), source);
  expect_error(dir + " " + dir + "/out.jsonl", 2, dir + ": is a directory, not a file");
  expect_error("/dev/zero " + dir + "/out.jsonl", 2,
               "/dev/zero: not a regular file");
  expect_error(in + " " + dir, 2, dir + ": is a directory, not an output file");
  expect_error(in + " " + dir + "/nope/out.jsonl", 2,
               dir + "/nope/out.jsonl: its folder " + dir + "/nope does not exist");
  // Where it cannot be opened for writing: bad input, named up front (not exit 4 from the first
  // write), and no file left behind.
  expect_error(in + " /proc/drapelab_out.jsonl", 2,
               "/proc/drapelab_out.jsonl: cannot be written: No such file or directory");
  expect_error(in + " /dev/full", 4, "cannot write /dev/full: No space left on device");
  // Past a file size limit (1 kB; the recording is about 30 kB) nothing half written stays.
  const std::string cut = dir + "/cut.jsonl";
  const int status = std::system(("sh -c 'ulimit -f 1; exec " + std::string(DRAPELAB_EXE) +
                                  " convert " + in + " " + cut + "' > /dev/null 2>&1")
                                     .c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 4);
  EXPECT_FALSE(std::filesystem::exists(cut)) << "a cut recording must not stay";
  // A symbolic link loop, as IN or as OUT.
  std::filesystem::create_symlink(dir + "/loop_b", dir + "/loop_a");
  std::filesystem::create_symlink(dir + "/loop_a", dir + "/loop_b");
  expect_error(dir + "/loop_a " + dir + "/out.jsonl", 2,
               dir + "/loop_a: Too many levels of symbolic links");
  expect_error(in + " " + dir + "/loop_a", 2, dir + "/loop_a: Too many levels of symbolic links");
  // A named pipe as OUT would wait for a reader for ever; an empty OUT is named.
  ASSERT_EQ(mkfifo((dir + "/pipe").c_str(), 0600), 0);
  expect_error(in + " " + dir + "/pipe", 2, dir + "/pipe: is a named pipe or socket, not a file to write");
  expect_error(in + " ''", 2, "OUT: is empty: name the file to write");
}

}  // namespace
