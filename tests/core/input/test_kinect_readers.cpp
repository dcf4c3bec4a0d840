#include "core/input/kinect_readers.hpp"

#include <gtest/gtest.h>

#include <map>
#include <sstream>

#include "tests/support/input_test_files.hpp"
#include "tests/support/test_support.hpp"

namespace drape {
namespace {

using test::expect_input_error;
using test::kinect_recording;
using test::test_dir;
using test::write_file;

/// A joint as the files give it: x, y, z and TrackingState.
using JointValues = std::array<std::string, 4>;

/// One KinectReader CSV line; joints not in `joints` are tracked at (0.1 j, 0.2, 2).
std::string csv_line(const std::string& tick, const std::map<int, JointValues>& joints,
                     bool trailing_comma = true) {
  std::ostringstream line;
  line << tick;
  for (int j = 0; j < 25; ++j) {
    const auto it = joints.find(j);
    const JointValues v =
        it != joints.end() ? it->second
                           : JointValues{std::to_string(0.1 * j), "0.2", "2", "2"};
    for (const auto& x : v) line << ',' << x;
  }
  if (trailing_comma) line << ',';
  return line.str() + "\n";
}

struct RealFile {
  const char* name;
  std::size_t frames;
  double seconds;  // last timestamp minus first, from the CSV's ticks
};

TEST(KinectV2Csv, RealRecordingsHaveTheDocumentedFramesAndDurations) {
  const RealFile files[] = {{"Ges01_wavehand.csv", 154, 5.1669343},
                            {"Ges02_balancinghands.csv", 161, 5.3999273},
                            {"Ges03_drawlines.csv", 213, 7.2339845},
                            {"Ges04_comehere.csv", 172, 5.865859},
                            {"Ges05_demopoint.csv", 190, 6.3658516},
                            {"Ges06_chickenwing.csv", 160, 5.3340675}};
  for (const auto& file : files) {
    SCOPED_TRACE(file.name);
    const Recording r = read_kinect_v2_csv(kinect_recording(file.name));
    EXPECT_EQ(r.source, kinect_recording(file.name));
    ASSERT_EQ(r.frames.size(), file.frames);
    EXPECT_EQ(r.frames.front().t, 0.0);
    EXPECT_NEAR(r.frames.back().t, file.seconds, 1e-12);
    for (std::size_t i = 1; i < r.frames.size(); ++i) {
      // About 33 ms per frame, dropped frames about 67 ms (data README).
      const double dt = r.frames[i].t - r.frames[i - 1].t;
      EXPECT_GT(dt, 0.026);
      EXPECT_LT(dt, 0.068);
    }
  }
}

TEST(KinectV2Csv, FirstFrameHandsEqualTheCsvNumbers) {
  const Recording r = read_kinect_v2_csv(kinect_recording("Ges01_wavehand.csv"));
  const HandFrame& f = r.frames.front();
  ASSERT_TRUE(f.right && f.left);
  EXPECT_EQ(f.right->position, Vec3(0.236557, -0.364566, 2.57116));
  EXPECT_FALSE(f.right->inferred);
  EXPECT_EQ(f.left->position, Vec3(-0.214305, -0.38063, 2.58584));
  EXPECT_TRUE(f.keys.empty());
}

TEST(KinectV2Csv, InferredCountsOfChickenWing) {
  const Recording r = read_kinect_v2_csv(kinect_recording("Ges06_chickenwing.csv"));
  int left_inferred = 0, right_inferred = 0;
  for (const auto& f : r.frames) {
    ASSERT_TRUE(f.left && f.right);  // every hand sample is tracked or inferred here
    left_inferred += f.left->inferred;
    right_inferred += f.right->inferred;
  }
  EXPECT_EQ(left_inferred, 99);
  EXPECT_EQ(right_inferred, 111);  // "right hand mostly only inferred"
}

TEST(KinectV2Csv, SyntheticValuesStatesAndRelativeTimes) {
  const auto dir = test_dir();
  const std::string text =
      csv_line("1000000", {{7, {"-0.5", "0.25", "2.5", "2"}}, {11, {"0.5", "0.125", "2", "1"}}}) +
      csv_line("1333333", {{7, {"0", "0", "0", "0"}}, {11, {"0.75", "1e-3", "2.25", "2"}}},
               false) +
      "\n" +
      csv_line("1700000", {{7, {"1", "2", "3", "1"}}, {11, {"9", "9", "9", "0"}}});
  const Recording r = read_kinect_v2_csv(write_file(dir, "synthetic.csv", text));
  ASSERT_EQ(r.frames.size(), 3u);
  EXPECT_EQ(r.frames[0].t, 0.0);
  EXPECT_EQ(r.frames[1].t, 0.0333333);
  EXPECT_EQ(r.frames[2].t, 0.07);
  EXPECT_EQ(r.frames[0].left->position, Vec3(-0.5, 0.25, 2.5));
  EXPECT_FALSE(r.frames[0].left->inferred);
  EXPECT_EQ(r.frames[0].right->position, Vec3(0.5, 0.125, 2));
  EXPECT_TRUE(r.frames[0].right->inferred);
  EXPECT_FALSE(r.frames[1].left);  // not tracked: no sample, never a made-up position
  EXPECT_EQ(r.frames[1].right->position, Vec3(0.75, 1e-3, 2.25));
  EXPECT_TRUE(r.frames[2].left->inferred);
  EXPECT_FALSE(r.frames[2].right);
  EXPECT_EQ(r.frame_places, (std::vector<std::string>{"line 1", "line 2", "line 4"}));
}

TEST(KinectV2Csv, BadInputNamesFileAndLine) {
  const auto dir = test_dir();
  const std::string good = csv_line("100", {});
  const auto check = [&](const std::string& name, const std::string& second_line,
                         std::initializer_list<std::string> parts) {
    SCOPED_TRACE(name);
    const std::string file = write_file(dir, name, good + second_line);
    std::vector<std::string> all{name};
    all.insert(all.end(), parts);
    try {
      read_kinect_v2_csv(file);
      ADD_FAILURE() << "expected an InputError";
    } catch (const InputError& e) {
      for (const auto& part : all)
        EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
  };
  check("nan.csv", csv_line("200", {{7, {"nan", "0", "2", "2"}}}), {"line 2: HandLeft.X"});
  check("inf.csv", csv_line("200", {{11, {"0", "inf", "2", "2"}}}), {"line 2: HandRight.Y"});
  check("text.csv", csv_line("200", {{3, {"0", "0", "abc", "2"}}}), {"line 2: Head.Z"});
  check("far.csv", csv_line("200", {{11, {"0", "1e300", "2", "2"}}}),
        {"line 2: HandRight.Y: must be within +-1000000.0"});
  check("state.csv", csv_line("200", {{11, {"0", "0", "2", "3"}}}),
        {"line 2: HandRight.TrackingState"});
  check("back.csv", csv_line("50", {}), {"line 2: timestamp", "increase"});
  check("same.csv", csv_line("100", {}), {"line 2: timestamp"});
  check("broken.csv", csv_line("200", {}).substr(0, 300) + "\n", {"line 2", "101 fields"});
  check("extra.csv", "200," + csv_line("300", {}), {"line 2", "101 fields"});
  expect_input_error([&] { read_kinect_v2_csv((dir / "missing.csv").string()); },
                     {"missing.csv", "cannot open"});
  expect_input_error([&] { read_kinect_v2_csv(write_file(dir, "empty.csv", "\n")); },
                     {"empty.csv", "no frames"});
}

/// One NTU body: info line, joint count, 25 joint lines; hands at the given positions.
std::string ntu_body(const std::string& id, const Vec3& left, const Vec3& right,
                     int left_state = 2, int right_state = 2, int joints = 25) {
  std::ostringstream s;
  s << id << " 0 1 1 1 1 0 -0.1 0.2 2\n" << joints << "\n";
  for (int j = 0; j < joints; ++j) {
    Vec3 p(0.01 * j, 0.5, 3.0);
    int state = 2;
    if (j == kinect_hand_left) p = left, state = left_state;
    if (j == kinect_hand_right) p = right, state = right_state;
    s << p.x() << ' ' << p.y() << ' ' << p.z() << " 250.5 200.25 900.5 500.75 0.5 0.5 0.5 0.5 "
      << state << "\n";
  }
  return s.str();
}

const std::string person = "72057594037931101";
const std::string other = "72057594037931102";

/// Four frames: the person; another body listed first and then the person (with an inferred
/// and an untracked hand); nobody; only the other body.
std::string ntu_text() {
  return "4\n1\n" + ntu_body(person, Vec3(-0.25, 0.5, 2.75), Vec3(0.25, 0.5, 2.5)) +  //
         "2\n" + ntu_body(other, Vec3(9, 9, 9), Vec3(9, 9, 9)) +
         ntu_body(person, Vec3(-0.125, 0.75, 2.5), Vec3(1, 1, 1), 1, 0) +  //
         "0\n" +                                                           //
         "1\n" + ntu_body(other, Vec3(8, 8, 8), Vec3(8, 8, 8));
}

TEST(KinectV2Csv, TimestampsWhoseDifferenceOverflowsAreInputErrors) {
  // Subtracting the first tick would overflow 64 bits (undefined behaviour).
  const std::string file =
      write_file(test_dir(), "overflow.csv",
                 csv_line("-9223372036854775807", {}) + csv_line("9223372036854775807", {}));
  try {
    read_kinect_v2_csv(file);
    ADD_FAILURE() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              file + ": line 2: timestamp: too far from the first frame's (the difference overflows 64 bits)");
  }
}

// A time `convert` could write but reading its output would refuse (1e11 s) is refused at once.
TEST(KinectV2Csv, TimesBeyondARecordingsSpanAreInputErrors) {
  const std::string file =
      write_file(test_dir(), "span.csv",
                 csv_line("0", {}) + csv_line("100000000000000000", {}) +  // 1e10 s: the bound
                     csv_line("100000000100000000", {}));
  try {
    read_kinect_v2_csv(file);
    ADD_FAILURE() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              file + ": line 3: timestamp: 10000000010 s after the first frame's, beyond the "
                     "+-1e+10 s a recording's times may span");
  }
}

TEST(NtuSkeleton, SyntheticFileFollowsTheFirstPerson) {
  const auto dir = test_dir();
  const Recording r = read_ntu_skeleton(write_file(dir, "synthetic.skeleton", ntu_text()));
  ASSERT_EQ(r.frames.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) EXPECT_EQ(r.frames[i].t, static_cast<double>(i) / 30.0);
  EXPECT_EQ(r.frames[0].left->position, Vec3(-0.25, 0.5, 2.75));
  EXPECT_EQ(r.frames[0].right->position, Vec3(0.25, 0.5, 2.5));
  EXPECT_EQ(r.frames[1].left->position, Vec3(-0.125, 0.75, 2.5));
  EXPECT_TRUE(r.frames[1].left->inferred);
  EXPECT_FALSE(r.frames[1].right);
  EXPECT_FALSE(r.frames[2].left || r.frames[2].right);
  EXPECT_FALSE(r.frames[3].left || r.frames[3].right);  // never another person's hands
  // Line 1 holds the frame count; a frame is its body count and 27 lines a body.
  EXPECT_EQ(r.frame_places,
            (std::vector<std::string>{"lines 2-29", "lines 30-84", "line 85", "lines 86-113"}));
}

TEST(NtuSkeleton, BadInputNamesFileAndLine) {
  const auto dir = test_dir();
  const std::string body = ntu_body(person, Vec3(0, 0, 2), Vec3(0, 0, 2));
  // Line numbers: 1 frame count, 2 body count, 3 info, 4 joint count, 5..29 joints.
  expect_input_error(
      [&] {
        read_ntu_skeleton(write_file(dir, "joints.skeleton",
                                     "1\n1\n" + ntu_body(person, Vec3(0, 0, 2), Vec3(0, 0, 2),
                                                         2, 2, 24)));
      },
      {"joints.skeleton", "line 4: joint count", "expected 25"});
  std::string nan_text = "1\n1\n" + body;
  nan_text.replace(nan_text.find("\n0 0 2 "), 7, "\nnan 0 2 ");  // joint 7 = HandLeft
  expect_input_error([&] { read_ntu_skeleton(write_file(dir, "nan.skeleton", nan_text)); },
                     {"nan.skeleton", "line 12: HandLeft.X", "finite"});
  std::string short_text = "1\n1\n" + body;
  short_text.replace(short_text.find(" 0.5 0.5 0.5 0.5 2\n"), 18, " 0.5 0.5 0.5 2\n");
  expect_input_error(
      [&] { read_ntu_skeleton(write_file(dir, "fields.skeleton", short_text)); },
      {"fields.skeleton", "line 5", "12 fields", "got 11"});
  expect_input_error(
      [&] { read_ntu_skeleton(write_file(dir, "early.skeleton", "2\n1\n" + body)); },
      {"early.skeleton", "line 30", "file ends early"});
  expect_input_error(
      [&] { read_ntu_skeleton(write_file(dir, "extra.skeleton", "1\n1\n" + body + "0\n")); },
      {"extra.skeleton", "line 30", "after the last"});
  expect_input_error(
      [&] { read_ntu_skeleton(write_file(dir, "count.skeleton", "x\n")); },
      {"count.skeleton", "line 1: the frame count"});
  expect_input_error([&] { read_ntu_skeleton(write_file(dir, "none.skeleton", "0\n")); },
                     {"none.skeleton", "no frames"});
  // Frames, but no body in any: it converted to frames without hands (exit 0).
  const auto bodiless = write_file(dir, "bodiless.skeleton", "3\n0\n0\n0\n");
  EXPECT_EQ(testing::input_error_message([&] { read_ntu_skeleton(bodiless); }),
            bodiless + ": no body in any of the 3 frames (every body count is 0): no hands to replay");
  // A body whose hand joints are never tracked (state 0): frames without hands too, not a
  // replay of nothing with exit 0.
  const std::string never = ntu_body(person, Vec3(0, 0, 2), Vec3(0, 0, 2), 0, 0);
  const auto untracked = write_file(dir, "untracked.skeleton", "2\n1\n" + never + "1\n" + never);
  EXPECT_EQ(testing::input_error_message([&] { read_ntu_skeleton(untracked); }),
            untracked + ": no hand tracked and no key in any of the 2 frames: nothing to replay");
}

// Every hand joint untracked (TrackingState 0) in every frame: the run would replay nothing,
// with status ok; one tracked frame is enough.
TEST(KinectV2Csv, ARecordingWithNoTrackedHandIsAnInputError) {
  const auto dir = test_dir();
  const JointValues untracked{"0", "0", "2", "0"};
  const std::string none = csv_line("100", {{7, untracked}, {11, untracked}});
  const auto file =
      write_file(dir, "untracked.csv", none + csv_line("200", {{7, untracked}, {11, untracked}}));
  EXPECT_EQ(testing::input_error_message([&] { read_kinect_v2_csv(file); }),
            file + ": no hand tracked and no key in any of the 2 frames: nothing to replay");
  const Recording one =
      read_kinect_v2_csv(write_file(dir, "one.csv", none + csv_line("200", {{11, untracked}})));
  EXPECT_TRUE(one.frames[1].left);
  EXPECT_FALSE(one.frames[1].right);
}

}  // namespace
}  // namespace drape
