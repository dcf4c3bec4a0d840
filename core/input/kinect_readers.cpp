#include "core/input/kinect_readers.hpp"

#include <fmt/format.h>

#include <cmath>
#include <optional>

#include "core/io/scene_limits.hpp"

namespace drape {

const std::array<const char*, 25> kinect_joint_names = {
    "SpineBase",     "SpineMid",     "Neck",          "Head",        "ShoulderLeft",
    "ElbowLeft",     "WristLeft",    "HandLeft",      "ShoulderRight", "ElbowRight",
    "WristRight",    "HandRight",    "HipLeft",       "KneeLeft",    "AnkleLeft",
    "FootLeft",      "HipRight",     "KneeRight",     "AnkleRight",  "FootRight",
    "SpineShoulder", "HandTipLeft",  "ThumbLeft",     "HandTipRight", "ThumbRight"};

namespace {

constexpr int joint_count = 25;
constexpr double ticks_per_second = 1e7;
constexpr double ntu_frames_per_second = 30.0;

/// One joint as both formats give it: a position and a Kinect TrackingState.
struct Joint {
  Vec3 position;
  TrackingState state;
};

// Shared by both readers: every joint is checked (finite coordinates, a valid state), not only
// the hands, because a corrupt joint anywhere means the line cannot be trusted.
Joint parse_joint(std::string_view x, std::string_view y, std::string_view z,
                  std::string_view state, const detail::TextLines& lines, int joint) {
  const std::string name = kinect_joint_names[static_cast<std::size_t>(joint)];
  Joint out{Vec3(detail::parse_finite(x, lines, name + ".X"),
                 detail::parse_finite(y, lines, name + ".Y"),
                 detail::parse_finite(z, lines, name + ".Z")),
            TrackingState::NotTracked};
  for (int k = 0; k < 3; ++k)
    if (!(std::abs(out.position[k]) <= limits::max_sensor_coordinate))
      throw lines.error(name + "." + "XYZ"[k],
                        "must be within +-" + nlohmann::json(limits::max_sensor_coordinate).dump());
  const long long s = detail::parse_integer(state, lines, name + ".TrackingState");
  if (s < 0 || s > 2)
    throw lines.error(name + ".TrackingState",
                      "expected 0 (not tracked), 1 (inferred) or 2 (tracked), got " +
                          std::to_string(s));
  out.state = static_cast<TrackingState>(s);
  return out;
}

std::optional<HandSample> hand_sample(const Joint& joint) {
  if (joint.state == TrackingState::NotTracked) return std::nullopt;
  return HandSample{joint.position, joint.state == TrackingState::Inferred};
}

/// The fields of the next line, which must exist and have `count` fields.
std::vector<std::string_view> next_fields(detail::TextLines& lines, std::string& line,
                                          std::size_t count, const std::string& what) {
  if (!lines.next(line))
    throw InputError(lines.file(), "line " + std::to_string(lines.number() + 1),
                     "file ends early: expected " + what);
  auto fields = detail::split_fields(line, ' ');
  if (fields.size() != count)
    throw lines.error("", "expected " + what + " (" + std::to_string(count) + " fields), got " +
                              std::to_string(fields.size()) + " fields");
  return fields;
}

long long next_count(detail::TextLines& lines, std::string& line, const std::string& what) {
  const auto fields = next_fields(lines, line, 1, what);
  const long long n = detail::parse_integer(fields[0], lines, what);
  if (n < 0) throw lines.error(what, "must not be negative");
  return n;
}

}  // namespace

Recording read_kinect_v2_csv(const std::string& file) {
  constexpr std::size_t field_count = 1 + 4 * joint_count;
  detail::TextLines lines(file);
  Recording recording{file, {}, {}};
  std::string line;
  long long first_tick = 0;
  while (lines.next(line)) {
    auto fields = detail::split_fields(line, ',');
    if (fields.size() == 1 && fields[0].empty()) continue;  // blank line
    // KinectReader ends every line with a comma: one empty field more.
    if (fields.size() == field_count + 1 && fields.back().empty()) fields.pop_back();
    if (fields.size() != field_count)
      throw lines.error("", "expected " + std::to_string(field_count) +
                                " fields (timestamp, then 25 joints as X, Y, Z, "
                                "TrackingState), got " + std::to_string(fields.size()));
    const long long tick = detail::parse_integer(fields[0], lines, "timestamp");
    if (recording.frames.empty()) first_tick = tick;
    HandFrame frame;
    // Differences of 64-bit ticks first, so that the seconds keep full precision.
    long long ticks = 0;
    if (__builtin_sub_overflow(tick, first_tick, &ticks))  // would be undefined behaviour
      throw lines.error("timestamp",
                        "too far from the first frame's (the difference overflows 64 bits)");
    frame.t = static_cast<double>(ticks) / ticks_per_second;
    // The bound every recording's times obey (docs/scene.md, Limits): `convert` wrote a time
    // beyond it that reading the converted file then refused.
    if (!(std::abs(frame.t) <= limits::max_recording_time))
      throw lines.error("timestamp", fmt::format("{:.0f} s after the first frame's, beyond the "
                                                 "+-{:g} s a recording's times may span",
                                                 frame.t, limits::max_recording_time));
    if (!recording.frames.empty())
      detail::check_time_order(recording.frames.back().t, frame.t, file,
                               lines.where("timestamp"));
    for (int j = 0; j < joint_count; ++j) {
      const std::size_t k = 1 + 4 * static_cast<std::size_t>(j);
      const Joint joint =
          parse_joint(fields[k], fields[k + 1], fields[k + 2], fields[k + 3], lines, j);
      if (j == kinect_hand_left) frame.left = hand_sample(joint);
      if (j == kinect_hand_right) frame.right = hand_sample(joint);
    }
    recording.frames.push_back(std::move(frame));
    recording.frame_places.push_back(lines.where());
  }
  if (recording.frames.empty()) throw InputError(file, "", "no frames");
  // Every hand joint untracked (TrackingState 0) in every frame: nothing is ever held.
  detail::check_something_to_replay(recording, file);
  return recording;
}

Recording read_ntu_skeleton(const std::string& file) {
  detail::TextLines lines(file);
  Recording recording{file, {}, {}};
  std::string line;
  const long long frame_total = next_count(lines, line, "the frame count");
  std::optional<std::string> person;  // body ID of the person whose hands are read
  for (long long f = 0; f < frame_total; ++f) {
    const int first_line = lines.number() + 1;
    HandFrame frame;
    frame.t = static_cast<double>(f) / ntu_frames_per_second;
    const long long bodies = next_count(lines, line, "the body count of frame " +
                                                         std::to_string(f + 1));
    for (long long b = 0; b < bodies; ++b) {
      const auto info = next_fields(lines, line, 10, "a body info line");
      const std::string body_id(info[0]);
      detail::parse_integer(info[0], lines, "bodyID");
      for (std::size_t i = 1; i < info.size(); ++i)
        detail::parse_finite(info[i], lines, "body info field " + std::to_string(i + 1));
      if (!person) person = body_id;
      const long long joints = next_count(lines, line, "the joint count");
      if (joints != joint_count)
        throw lines.error("joint count", "expected 25 (Kinect v2 joints), got " +
                                             std::to_string(joints));
      for (int j = 0; j < joint_count; ++j) {
        const auto v = next_fields(lines, line, 12,
                                   std::string("joint ") + kinect_joint_names[j] +
                                       " (x y z depthX depthY colorX colorY qW qX qY qZ "
                                       "trackingState)");
        for (std::size_t i = 3; i < 11; ++i)
          detail::parse_finite(v[i], lines, std::string(kinect_joint_names[j]) + " field " +
                                                std::to_string(i + 1));
        const Joint joint = parse_joint(v[0], v[1], v[2], v[11], lines, j);
        if (body_id != *person) continue;
        if (j == kinect_hand_left) frame.left = hand_sample(joint);
        if (j == kinect_hand_right) frame.right = hand_sample(joint);
      }
    }
    recording.frames.push_back(std::move(frame));
    recording.frame_places.push_back(
        first_line == lines.number()
            ? lines.where()
            : "lines " + std::to_string(first_line) + "-" + std::to_string(lines.number()));
  }
  while (lines.next(line))
    if (!detail::split_fields(line, ' ').empty())
      throw lines.error("", "data after the last of the " + std::to_string(frame_total) +
                                " frames the file announces");
  // As the other readers: a replay without frames would run without hands as if nothing were wrong.
  if (recording.frames.empty()) throw InputError(file, "", "no frames (the frame count is 0)");
  // Nor would frames without a body: every hand absent, nothing ever held.
  if (!person)
    throw InputError(file, "", "no body in any of the " + std::to_string(frame_total) +
                                   " frames (every body count is 0): no hands to replay");
  // Bodies whose hand joints are never tracked replay nothing either.
  detail::check_something_to_replay(recording, file);
  return recording;
}

}  // namespace drape
