#include "core/input/input_config.hpp"

#include <gtest/gtest.h>

#include "core/input/kinect_readers.hpp"
#include "tests/support/input_test_files.hpp"

namespace drape {
namespace {

using nlohmann::json;
using test::expect_input_error;

/// The directory that scene paths in these tests are relative to.
std::filesystem::path scene_dir() {
  return std::filesystem::path(DRAPE_SOURCE_DIR) / "experiments";
}

InputConfig parse(const std::string& text) {
  return parse_input_config(json::parse(text), "scenes/s.json", "input", scene_dir());
}

TEST(InputConfig, DefaultsOfAnEmptyObject) {
  const InputConfig c = parse("{}");
  EXPECT_TRUE(c.recording.empty());
  EXPECT_TRUE(c.events.empty());
  EXPECT_EQ(c.transform.scale, 1.0);
  EXPECT_EQ(c.transform.rotation, Mat3::Identity());
  EXPECT_EQ(c.transform.translation, Vec3::Zero());
  EXPECT_EQ(c.time.offset, 0.0);
  EXPECT_EQ(c.time.scale, 1.0);
  EXPECT_EQ(c.track.inferred, InferredPolicy::Use);
  EXPECT_EQ(c.track.max_gap, 0.15);
  EXPECT_EQ(c.track.smoothing.filter, SmoothingFilter::None);
  const HandInput input = load_hand_input(c);
  EXPECT_TRUE(input.source.empty());
  EXPECT_FALSE(input.track.span(Hand::Left) || input.track.span(Hand::Right));
  EXPECT_TRUE(input.track.keys().empty());
}

TEST(InputConfig, ReadsEveryKeyAndLoadsTheRecording) {
  const std::string text = R"({
    "recording": "recordings/kinect-v2/Ges01_wavehand.csv",
    "format": "kinect-v2-csv",
    "events": [{"t": 1.0, "keys": ["a"]}, {"t": 2.0, "keys": ["r"]}],
    "transform": {"scale": 2, "rotation": [-1, 0, 0, 0, 1, 0, 0, 0, -1],
                  "translation": [0, 1, 3]},
    "time_offset": 0.5, "time_scale": 2,
    "inferred": "drop", "max_gap": 0.2,
    "smoothing": {"filter": "one-euro", "min_cutoff": 1.5, "beta": 0.25, "d_cutoff": 2}
  })";
  const InputConfig c = parse(text);
  EXPECT_EQ(c.recording,
            (scene_dir() / "recordings/kinect-v2/Ges01_wavehand.csv").lexically_normal().string());
  EXPECT_EQ(c.format, RecordingFormat::KinectV2Csv);
  ASSERT_EQ(c.events.size(), 2u);
  EXPECT_EQ(c.transform.scale, 2.0);
  EXPECT_EQ(c.transform.rotation(0, 0), -1.0);
  EXPECT_EQ(c.transform.rotation(2, 2), -1.0);
  EXPECT_EQ(c.transform.translation, Vec3(0, 1, 3));
  EXPECT_EQ(c.time.offset, 0.5);
  EXPECT_EQ(c.time.scale, 2.0);
  EXPECT_EQ(c.track.inferred, InferredPolicy::Drop);
  EXPECT_EQ(c.track.max_gap, 0.2);
  EXPECT_EQ(c.track.smoothing.filter, SmoothingFilter::OneEuro);
  EXPECT_EQ(c.track.smoothing.min_cutoff, 1.5);
  EXPECT_EQ(c.track.smoothing.beta, 0.25);
  EXPECT_EQ(c.track.smoothing.d_cutoff, 2.0);

  const HandInput input = load_hand_input(c);
  EXPECT_EQ(input.source, c.recording);
  // The first frame's HandRight (0.236557, -0.364566, 2.57116) mapped to the scene; the
  // filter starts at the first sample, so smoothing leaves it as it is.
  const auto first = *input.track.motion(Hand::Right, 0.5);
  EXPECT_TRUE(first.available);
  EXPECT_NEAR((first.position - Vec3(-2 * 0.236557, 2 * -0.364566 + 1, -2 * 2.57116 + 3)).norm(),
              0.0, 1e-14);
  // Event keys go through the same time map as the recording.
  const std::vector<KeyEvent> keys = {{2.5, "a"}, {4.5, "r"}};
  EXPECT_EQ(input.track.keys(), keys);
}

TEST(InputConfig, NestedAndFlatRotationsAgree) {
  const InputConfig flat = parse(R"({"transform": {"rotation": [0, 0, 1, 0, 1, 0, -1, 0, 0]}})");
  const InputConfig rows =
      parse(R"({"transform": {"rotation": [[0, 0, 1], [0, 1, 0], [-1, 0, 0]]}})");
  EXPECT_EQ(flat.transform.rotation, rows.transform.rotation);
  EXPECT_EQ(flat.transform.rotation(0, 2), 1.0);
  EXPECT_EQ(flat.transform.rotation(2, 0), -1.0);
}

TEST(InputConfig, EventsAloneGiveHandsAndKeys) {
  const HandInput input = load_hand_input(
      json::parse(R"({"events": [{"t": 0, "right": [0, 0, 0]},
                                 {"t": 0.1, "right": [0.1, 0, 0], "keys": ["a"]},
                                 {"t": 0.2, "right": [0.2, 0, 0]}],
                      "transform": {"translation": [0, 1, 0]}})"),
      "s.json", "input", ".");
  EXPECT_EQ(input.source, "input.events");
  const auto m = *input.track.motion(Hand::Right, 0.15);
  EXPECT_NEAR((m.position - Vec3(0.15, 1, 0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((m.velocity - Vec3(1, 0, 0)).norm(), 0.0, 1e-12);
  EXPECT_EQ(input.track.keys(), (std::vector<KeyEvent>{{0.1, "a"}}));
}

// Every point of the hand's curve, not only its samples, lies within the scene bound: samples
// 1 us apart and 1 cm apart give a tangent of 1e4 m/s, which throws the cubic 250 m out over
// the next 0.1 s; samples a denormal apart give a tangent that is not finite.
TEST(InputConfig, TheCurveBetweenSamplesMustStayWithinTheSceneBound) {
  const auto load = [](const std::string& events) {
    return load_hand_input(json::parse(R"({"events": )" + events + "}"), "s.json", "input", ".");
  };
  expect_input_error(
      [&] {
        load(R"([{"t": 0, "right": [0, 1, 0]}, {"t": 1e-6, "right": [0.01, 1, 0]},
                 {"t": 0.1, "right": [0.02, 1, 0]}])");
      },
      {"s.json: input.events: the right hand's curve between t = 1e-06 s and t = 0.1 s",
       "reaches 250.0", "m in x", "+-10 m"});
  expect_input_error(
      [&] { load(R"([{"t": 0, "right": [0, 1, 0]}, {"t": 5e-324, "right": [0.02, 1, 0]}])"); },
      {"is not finite in x"});
  // Kinect frames 33 ms apart with a 1 m jump (a tracking glitch) stay within the bound.
  const HandInput glitch = load(R"([{"t": 0, "left": [0, 1, 0]}, {"t": 0.033, "left": [1, 1, 0]},
                                    {"t": 0.067, "left": [0, 1, 0]}])");
  EXPECT_TRUE(glitch.track.motion(Hand::Left, 0.05).has_value());
}

TEST(InputConfig, WrittenJsonReadsBackTheSame) {
  const InputConfig c = parse(R"({
    "recording": "recordings/kinect-v2/Ges04_comehere.csv",
    "events": [{"t": 1.25, "keys": ["m"]}],
    "transform": {"scale": 0.5, "rotation": [[0, -1, 0], [1, 0, 0], [0, 0, 1]],
                  "translation": [1, 2, 3]},
    "time_offset": -1, "inferred": "drop", "smoothing": {"filter": "one-euro", "beta": 2}})");
  const InputConfig back = parse_input_config(input_config_to_json(c), "out/input.json",
                                              "input", "/nowhere");
  EXPECT_EQ(back.recording, c.recording);
  EXPECT_EQ(back.format, c.format);
  EXPECT_EQ(back.events, c.events);
  EXPECT_EQ(back.transform.scale, c.transform.scale);
  EXPECT_EQ(back.transform.rotation, c.transform.rotation);
  EXPECT_EQ(back.transform.translation, c.transform.translation);
  EXPECT_EQ(back.time.offset, c.time.offset);
  EXPECT_EQ(back.time.scale, c.time.scale);
  EXPECT_EQ(back.track.inferred, c.track.inferred);
  EXPECT_EQ(back.track.max_gap, c.track.max_gap);
  EXPECT_EQ(back.track.smoothing.filter, c.track.smoothing.filter);
  EXPECT_EQ(back.track.smoothing.beta, 2.0);
}

TEST(InputConfig, ErrorsNameTheSceneFileAndTheDottedPath) {
  const auto bad = [](const std::string& text, std::initializer_list<std::string> parts) {
    SCOPED_TRACE(text);
    expect_input_error([&] { parse(text); }, {"scenes/s.json"});
    expect_input_error([&] { parse(text); }, parts);
  };
  bad(R"({"recordings": "a.csv"})", {"input.recordings", "unknown key"});
  bad(R"({"recording": "nope.csv"})", {"input.recording", "no such file"});
  bad(R"({"format": "kinect-v2-csv"})", {"input.format", "input.recording"});
  bad(R"({"recording": "recordings/kinect-v2/Ges01_wavehand.csv", "format": "bvh"})",
      {"input.format", "\"ntu-skeleton\""});
  bad(R"({"transform": {"scale": -1}})", {"input.transform.scale", "positive"});
  bad(R"({"transform": {"scale": "big"}})", {"input.transform.scale"});
  bad(R"({"transform": {"rotation": [1, 0, 0, 0, 1, 0, 0, 0.5, 1]}})",
      {"input.transform.rotation", "not a rotation"});
  bad(R"({"transform": {"rotation": [[1, 0, 0], [0, 1, 0]]}})", {"input.transform.rotation"});
  bad(R"({"transform": {"rotation": [1, 0, 0, 0, 1, 0, 0, 0]}})", {"input.transform.rotation"});
  bad(R"({"transform": {"rotation": []}})", {"input.transform.rotation", "got []"});  // crashed
  bad(R"({"transform": {"translation": [0, 1]}})", {"input.transform.translation"});
  bad(R"({"transform": {"shift": [0, 1, 0]}})", {"input.transform.shift", "unknown key"});
  bad(R"({"time_scale": 0})", {"input.time_scale", "positive"});
  bad(R"({"time_scale": 1e-300})", {"input.time_scale: must be at least 0.001"});
  bad(R"({"time_scale": 1e300})", {"input.time_scale: must be at most 1000.0"});
  bad(R"({"time_offset": 1e300})", {"input.time_offset: must be within +-10000000000.0"});
  // Hands are checked in the scene frame, where the live mode checks them too.
  bad(R"({"events": [{"t": 0}, {"t": 1, "right": [1e300, 0, 0]}]})",
      {"input.events[1].right: must be within +-1000000.0"});
  bad(R"({"events": [{"t": 0, "left": [0, 1, 0]}, {"t": 1, "right": [0, 20, 0]}]})",
      {"input.events[1].right.y: 20 is not a scene coordinate within +-10 m"});
  bad(R"({"events": [{"t": 0, "left": [0, 1, 0]}], "transform": {"scale": 100}})",
      {"input.events[0].left.y: 100 is not a scene coordinate within +-10 m"});
  bad(R"({"max_gap": -0.1})", {"input.max_gap"});
  bad(R"({"inferred": "maybe"})", {"input.inferred", "\"use\", \"drop\""});
  bad(R"({"smoothing": {"filter": "kalman"}})", {"input.smoothing.filter"});
  bad(R"({"smoothing": {"min_cutoff": 0}})", {"input.smoothing.min_cutoff"});
  bad(R"({"smoothing": {"beta": -1}})", {"input.smoothing.beta"});
  bad(R"({"smoothing": {"alpha": 1}})", {"input.smoothing.alpha", "unknown key"});
  bad(R"({"events": [{"t": 0}, {"t": "x"}]})", {"input.events[1].t"});
  bad(R"({"recording": "recordings/kinect-v2/Ges01_wavehand.csv",
          "events": [{"t": 0, "keys": ["a"]}, {"t": 1, "left": [0, 0, 0]}]})",
      {"input.events[1]", "only add keys"});
  expect_input_error(
      [] { parse_input_config(json::parse("[1]"), "scenes/s.json", "input", scene_dir()); },
      {"scenes/s.json", "input", "object"});
}

TEST(InputConfig, ErrorsInsideTheRecordingNameItsLine) {
  const auto dir = test::test_dir();
  const auto error_of = [&](const std::string& frames, std::initializer_list<std::string> parts) {
    test::write_file(dir, "r.jsonl",
                     "{\"format\": \"drapelab-recording\", \"version\": 1}\n" + frames);
    expect_input_error(
        [&] { load_hand_input(json::parse(R"({"recording": "r.jsonl"})"), "s.json", "input", dir); },
        parts);
  };
  error_of("{\"t\": 0}\n{\"t\": 0}\n", {"r.jsonl", "line 3.t"});
  // Hands are checked in the scene frame, frame by frame, and named by their line.
  error_of("{\"t\": 0, \"left\": [0, 1, 0]}\n{\"t\": 0.5, \"left\": [0, 11, 0]}\n",
           {"r.jsonl: line 3 (frame 2, t = 0.5 s).left.y: 11 is not a scene coordinate within +-10 m"});
}

}  // namespace
}  // namespace drape
