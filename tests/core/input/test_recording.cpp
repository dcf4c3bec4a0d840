#include "core/input/recording.hpp"

#include <gtest/gtest.h>

#include <array>

#include "core/input/kinect_readers.hpp"
#include "tests/support/input_test_files.hpp"
#include "tests/support/test_support.hpp"

namespace drape {
namespace {

using test::expect_input_error;
using test::kinect_recording;
using test::test_dir;
using test::write_file;

const std::string header = "{\"format\": \"drapelab-recording\", \"version\": 1}\n";

Recording sample_recording() {
  Recording r;
  r.source = "memory";
  HandFrame a;
  a.t = 0.1 + 0.2;  // not a short decimal: checks round-trip precision
  a.left = HandSample{Vec3(1.0 / 3.0, -2.5e-7, 2.718281828459045), false};
  a.right = HandSample{Vec3(0.1, 0.2, 0.3), true};
  a.keys = {"a", "m"};
  HandFrame b;
  b.t = 1.0 / 3.0;
  b.right = HandSample{Vec3(-1e6, 5e-324, 0.0), false};  // the bound itself, and a denormal
  HandFrame c;
  c.t = 2.0;
  c.keys = {"r"};
  r.frames = {a, b, c};
  return r;
}

TEST(Recording, NativeRoundTripIsExact) {
  const auto dir = test_dir();
  const Recording r = sample_recording();
  const auto file = (dir / "r.jsonl").string();
  write_drapelab_recording(r, file);
  const Recording back = read_drapelab_recording(file);
  EXPECT_EQ(back.source, file);
  EXPECT_EQ(back.frames, r.frames);
  EXPECT_EQ(detect_recording_format(file), RecordingFormat::Drapelab);
}

TEST(Recording, ReadsTheSpecExampleWithOmittedFields) {
  const auto dir = test_dir();
  const auto file = write_file(dir, "spec.jsonl",
                               header +
                                   "{\"t\": 0.033, \"left\": [1, 2, 3], \"right\": null, "
                                   "\"keys\": [\"a\"]}\r\n\n"
                                   "{\"t\": 0.066}\n"
                                   "{\"t\": 0.1, \"right\": [4, 5, 6], "
                                   "\"inferred\": [\"right\"]}\n");
  const Recording r = read_recording(file);
  ASSERT_EQ(r.frames.size(), 3u);
  EXPECT_EQ(r.frame_places, (std::vector<std::string>{"line 2", "line 4", "line 5"}));
  EXPECT_EQ(r.frames[0].t, 0.033);
  EXPECT_EQ(r.frames[0].left->position, Vec3(1, 2, 3));
  EXPECT_FALSE(r.frames[0].right);
  EXPECT_EQ(r.frames[0].keys, std::vector<std::string>{"a"});
  EXPECT_FALSE(r.frames[1].left || r.frames[1].right);
  EXPECT_TRUE(r.frames[1].keys.empty());
  EXPECT_TRUE(r.frames[2].right->inferred);
}

TEST(Recording, ConvertKinectCsvThenReadGivesIdenticalFrames) {
  const auto dir = test_dir();
  for (const char* name : {"Ges01_wavehand.csv", "Ges06_chickenwing.csv"}) {
    SCOPED_TRACE(name);
    const auto in = kinect_recording(name);
    const auto out = (dir / (std::string(name) + ".jsonl")).string();
    EXPECT_EQ(detect_recording_format(in), RecordingFormat::KinectV2Csv);
    convert_recording(in, out);
    EXPECT_EQ(read_drapelab_recording(out).frames, read_kinect_v2_csv(in).frames);
  }
}

TEST(Recording, ConvertNtuSkeletonThenReadGivesIdenticalFrames) {
  const auto dir = test_dir();
  std::string text = "2\n";
  for (int f = 0; f < 2; ++f) {
    text += "1\n72057594037931101 0 1 1 1 1 0 0 0 2\n25\n";
    for (int j = 0; j < 25; ++j)
      text += std::to_string(0.01 * j + f) + " 0.5 2.5 1 2 3 4 1 0 0 0 " +
              (j == kinect_hand_right ? "1" : "2") + "\n";
  }
  const auto in = write_file(dir, "two.skeleton", text);
  EXPECT_EQ(detect_recording_format(in), RecordingFormat::NtuSkeleton);
  const auto out = (dir / "two.jsonl").string();
  convert_recording(in, out);
  const Recording back = read_recording(out);
  ASSERT_EQ(back.frames.size(), 2u);
  EXPECT_EQ(back.frames, read_ntu_skeleton(in).frames);
  EXPECT_EQ(back.frames[1].t, 1.0 / 30.0);
  EXPECT_EQ(back.frames[1].left->position, Vec3(1.07, 0.5, 2.5));
  EXPECT_TRUE(back.frames[1].right->inferred);
}

TEST(Recording, InlineFramesAndTheirErrors) {
  const auto events = nlohmann::json::parse(
      R"([{"t": 0.5, "keys": ["a"]}, {"t": 1.5, "left": [0, 1, 2], "keys": ["r", "m"]}])");
  const auto frames = read_inline_frames(events, "scene.json", "input.events");
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(frames[1].t, 1.5);
  EXPECT_EQ(frames[1].left->position, Vec3(0, 1, 2));
  EXPECT_EQ(frames[1].keys, (std::vector<std::string>{"r", "m"}));

  const auto bad = [](const std::string& text, std::initializer_list<std::string> parts) {
    SCOPED_TRACE(text);
    expect_input_error(
        [&] { read_inline_frames(nlohmann::json::parse(text), "scene.json", "input.events"); },
        parts);
  };
  bad(R"([{"t": 0}, {"t": 1, "left": [0, 1]}])", {"scene.json", "input.events[1].left"});
  bad(R"([{"t": 0}, {"keys": ["a"]}])", {"input.events[1].t", "missing"});
  bad(R"([{"t": 1}, {"t": 0.5}])", {"input.events[1].t", "increase"});
  bad(R"([{"t": 0, "hand": [0, 0, 0]}])", {"input.events[0].hand", "unknown key"});
  bad(R"([{"t": 0, "keys": "a"}])", {"input.events[0].keys"});
  bad(R"([{"t": 0, "keys": [""]}])", {"input.events[0].keys"});
  bad(R"([{"t": 0, "keys": ["zz"]}])", {"input.events[0].keys", "got \"zz\""});
  bad(R"([{"t": 0, "inferred": ["left"]}])", {"input.events[0].inferred", "absent"});
  bad(R"({"t": 0})", {"input.events", "array"});
}

TEST(Recording, BadNativeFilesNameFileAndLine) {
  const auto dir = test_dir();
  const auto check = [&](const std::string& name, const std::string& text,
                         std::initializer_list<std::string> parts) {
    SCOPED_TRACE(name);
    const auto file = write_file(dir, name, text);
    expect_input_error([&] { read_drapelab_recording(file); }, {name});
    expect_input_error([&] { read_drapelab_recording(file); }, parts);
  };
  const std::string frame1 = "{\"t\": 0, \"left\": [0, 0, 0]}\n";
  check("broken.jsonl", header + frame1 + "{\"t\": 1, \"left\": [0, 0\n", {"line 3", "JSON"});
  check("nan.jsonl", header + frame1 + "{\"t\": 1, \"left\": [NaN, 0, 0]}\n", {"line 3"});
  check("huge.jsonl", header + frame1 + "{\"t\": 1, \"left\": [1e999, 0, 0]}\n",
        {"line 3", "overflow"});
  check("missing.jsonl", header + frame1 + "{\"left\": [0, 0, 0]}\n", {"line 3.t", "missing"});
  check("back.jsonl", header + frame1 + "{\"t\": -1}\n", {"line 3.t", "increase"});
  check("unknown.jsonl", header + frame1 + "{\"t\": 1, \"speed\": 2}\n",
        {"line 3.speed", "unknown key"});
  check("header.jsonl", "{\"format\": \"csv\", \"version\": 1}\n" + frame1,
        {"line 1 (header).format"});
  check("version.jsonl", "{\"format\": \"drapelab-recording\", \"version\": 2}\n",
        {"line 1 (header).version"});
  check("empty.jsonl", "\n", {"header"});
  // Values no sensor gives, and files that would replay nothing.
  check("far.jsonl", header + frame1 + "{\"t\": 1, \"right\": [0, 1e300, 0]}\n",
        {"line 3.right: must be within +-1000000.0"});
  check("late.jsonl", header + frame1 + "{\"t\": 1e300}\n",
        {"line 3.t: must be within +-10000000000.0"});
  check("key.jsonl", header + frame1 + "{\"t\": 1, \"keys\": [\"a\", \"zz\"]}\n",
        {"line 3.keys: expected \"r\" (release), \"a\" (attach) or \"m\" (map), got \"zz\""});
  check("frameless.jsonl", header + "\n", {"frameless.jsonl: no frames after the header"});
  check("handless.jsonl", header + "{\"t\": 0, \"left\": null}\n{\"t\": 1}\n",
        {"handless.jsonl: no hand tracked and no key in any of the 2 frames: nothing to replay"});
  // A Unix timestamp is a recording time.
  const auto unix_time =
      write_file(dir, "unix.jsonl", header + "{\"t\": 1732700000.5, \"right\": [0, 1, 2]}\n");
  EXPECT_EQ(read_drapelab_recording(unix_time).frames.at(0).t, 1732700000.5);
}

TEST(Recording, FormatDetectionRejectsUnknownContent) {
  const auto dir = test_dir();
  expect_input_error(
      [&] { detect_recording_format(write_file(dir, "what.txt", "\nhello world\n")); },
      {"what.txt", "line 2", "format"});
  // An empty file has no line to name (it was reported at "line 0").
  for (const auto& [name, text, message] :
       {std::array<std::string, 3>{"empty.jsonl", "", "empty file: no recording"},
        std::array<std::string, 3>{"blank.jsonl", "\n  \n", "only blank lines: no recording"}}) {
    const auto file = write_file(dir, name, text);
    EXPECT_EQ(testing::input_error_message([&] { read_recording(file); }), file + ": " + message);
  }
}

// A byte order mark (Windows editors write one) hid the header's '{': the file was taken for a
// Kinect CSV because the header holds a comma. Every format reads past it.
TEST(Recording, AByteOrderMarkIsNotPartOfTheFirstLine) {
  const auto dir = test_dir();
  const std::string bom = "\xEF\xBB\xBF";
  const std::string frames = "{\"t\": 0, \"left\": [0, 0, 0]}\n{\"t\": 0.5, \"right\": [1, 2, 3]}\n";
  const auto plain = write_file(dir, "plain.jsonl", header + frames);
  const auto marked = write_file(dir, "bom.jsonl", bom + header + frames);
  EXPECT_EQ(detect_recording_format(marked), RecordingFormat::Drapelab);
  EXPECT_EQ(read_recording(marked).frames, read_recording(plain).frames);
  const auto ntu = write_file(dir, "bom.skeleton", bom + "0\n");
  EXPECT_EQ(detect_recording_format(ntu), RecordingFormat::NtuSkeleton);
}

TEST(TextHelpers, SplitAndParse) {
  using detail::split_fields;
  EXPECT_EQ(split_fields("  a \t b  c ", ' '),
            (std::vector<std::string_view>{"a", "b", "c"}));
  EXPECT_EQ(split_fields("1, 2,,3,", ','),
            (std::vector<std::string_view>{"1", "2", "", "3", ""}));
  EXPECT_TRUE(split_fields("   ", ' ').empty());
}

}  // namespace
}  // namespace drape
