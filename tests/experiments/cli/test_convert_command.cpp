// `drapelab convert`: frames, duration and dropped frames of a recording.
#include "experiments/cli/convert_command.hpp"

#include <gtest/gtest.h>

#include <cstdio>

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

}  // namespace
