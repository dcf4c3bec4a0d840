#include "core/input/recording.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "core/io/json_reader.hpp"
#include "core/io/json_text.hpp"
#include "core/io/output_error.hpp"
#include "core/io/scene_limits.hpp"
#include "core/input/kinect_readers.hpp"

namespace drape {
namespace {

constexpr const char* native_format = "drapelab-recording";
constexpr int native_version = 1;

std::optional<HandSample> read_hand(JsonReader& reader, const std::string& key) {
  if (!reader.has(key) || reader.raw(key).is_null()) return std::nullopt;
  return HandSample{reader.within(key, reader.vec3(key), limits::max_sensor_coordinate), false};
}

// The one frame parser of the native format, shared by the JSON Lines reader and the inline
// `input.events`, so that both accept exactly the same objects.
HandFrame read_frame(const nlohmann::json& object, const std::string& file,
                     const std::string& path) {
  JsonReader reader(object, file, path);
  HandFrame frame;
  frame.t = reader.within("t", reader.number("t"), limits::max_recording_time);
  frame.left = read_hand(reader, "left");
  frame.right = read_hand(reader, "right");
  if (reader.has("keys")) {
    const auto& keys = reader.raw("keys");
    if (!keys.is_array()) throw reader.error("keys", "expected an array of key names");
    const auto& known = manipulation_keys();
    for (const auto& key : keys) {
      if (!key.is_string() ||
          std::find(known.begin(), known.end(), key.get<std::string>()) == known.end())
        throw reader.error("keys", "expected \"r\" (release), \"a\" (attach) or \"m\" (map), got " +
                                       quote_json(key));
      frame.keys.push_back(key.get<std::string>());
    }
  }
  if (reader.has("inferred")) {
    const auto& hands = reader.raw("inferred");
    if (!hands.is_array()) throw reader.error("inferred", "expected an array of hand names");
    for (const auto& hand : hands) {
      if (hand != "left" && hand != "right")
        throw reader.error("inferred", "expected \"left\" or \"right\", got " + quote_json(hand));
      auto& sample = hand == "left" ? frame.left : frame.right;
      if (!sample)
        throw reader.error("inferred", hand.get<std::string>() + " hand is null or absent");
      sample->inferred = true;
    }
  }
  reader.finish();
  return frame;
}

nlohmann::ordered_json hand_to_json(const std::optional<HandSample>& hand) {
  if (!hand) return nullptr;
  return {hand->position.x(), hand->position.y(), hand->position.z()};
}

}  // namespace

const std::vector<std::string>& manipulation_keys() {
  static const std::vector<std::string> keys = {"r", "a", "m"};
  return keys;
}

RecordingFormat detect_recording_format(const std::string& file) {
  // The content decides, not the extension: the three formats differ on their first line
  // (a JSON object, a comma-separated frame, a lone frame count).
  detail::TextLines lines(file);
  std::string line;
  while (lines.next(line)) {
    const auto fields = detail::split_fields(line, ' ');
    if (fields.empty()) continue;
    if (fields.front().front() == '{') return RecordingFormat::Drapelab;
    if (line.find(',') != std::string::npos) return RecordingFormat::KinectV2Csv;
    if (fields.size() == 1) return RecordingFormat::NtuSkeleton;
    throw lines.error("", "cannot tell the recording format (drapelab JSON Lines, Kinect v2 CSV "
                          "or NTU .skeleton) from the first line");
  }
  // No line to name ("line 0" before): the file says nothing.
  throw InputError(file, "", lines.number() == 0 ? "empty file: no recording"
                                                 : "only blank lines: no recording");
}

Recording read_drapelab_recording(const std::string& file) {
  detail::TextLines lines(file);
  Recording recording{file, {}, {}};
  std::string line;
  bool header = false;
  while (lines.next(line)) {
    if (detail::split_fields(line, ' ').empty()) continue;
    if (!header) {
      read_drapelab_header_line(line, file, lines.where());
      header = true;
      continue;
    }
    HandFrame frame = read_drapelab_frame_line(line, file, lines.where());
    if (!recording.frames.empty())
      detail::check_time_order(recording.frames.back().t, frame.t, file, lines.where() + ".t");
    recording.frames.push_back(std::move(frame));
    recording.frame_places.push_back(lines.where());
  }
  if (!header) throw InputError(file, "", "empty file: expected the drapelab-recording header");
  // A replay with no frames would run without hands as if nothing were wrong (as the Kinect
  // readers refuse an empty file).
  if (recording.frames.empty()) throw InputError(file, "", "no frames after the header");
  detail::check_something_to_replay(recording, file);
  return recording;
}

void read_drapelab_header_line(const std::string& line, const std::string& file,
                               const std::string& where) {
  // Syntax, numbers out of range and nesting beyond max_json_depth, naming the line.
  const nlohmann::json object = parse_json_text(line, file, where);
  JsonReader reader(object, file, where + " (header)");
  if (reader.string("format") != native_format)
    throw reader.error("format", std::string("expected \"") + native_format + "\"");
  if (reader.integer("version") != native_version)
    throw reader.error("version", "only version 1 is supported");
  reader.finish();
}

HandFrame read_drapelab_frame_line(const std::string& line, const std::string& file,
                                   const std::string& where) {
  return read_frame(parse_json_text(line, file, where), file, where);
}

nlohmann::ordered_json frame_to_json(const HandFrame& frame) {
  nlohmann::ordered_json object;
  object["t"] = frame.t;
  object["left"] = hand_to_json(frame.left);
  object["right"] = hand_to_json(frame.right);
  if (!frame.keys.empty()) object["keys"] = frame.keys;
  nlohmann::ordered_json inferred = nlohmann::ordered_json::array();
  if (frame.left && frame.left->inferred) inferred.push_back("left");
  if (frame.right && frame.right->inferred) inferred.push_back("right");
  if (!inferred.empty()) object["inferred"] = inferred;
  return object;
}

void write_drapelab_recording(const Recording& recording, const std::string& file) {
  errno = 0;
  std::ofstream out(file);
  if (!out) throw write_failure(file);
  // nlohmann writes doubles in their shortest round-trip form, so reading back is exact.
  out << nlohmann::ordered_json{{"format", native_format}, {"version", native_version}}.dump()
      << '\n';
  for (const auto& frame : recording.frames) out << frame_to_json(frame).dump() << '\n';
  out.flush();
  if (!out) fail_write(file);
}

Recording read_recording(const std::string& file, RecordingFormat format) {
  if (format == RecordingFormat::Auto) format = detect_recording_format(file);
  switch (format) {
    case RecordingFormat::KinectV2Csv: return read_kinect_v2_csv(file);
    case RecordingFormat::NtuSkeleton: return read_ntu_skeleton(file);
    case RecordingFormat::Drapelab:
    case RecordingFormat::Auto: break;
  }
  return read_drapelab_recording(file);
}

void convert_recording(const std::string& in, const std::string& out) {
  write_drapelab_recording(read_recording(in), out);
}

std::vector<HandFrame> read_inline_frames(const nlohmann::json& events, const std::string& file,
                                          const std::string& field_path) {
  if (!events.is_array())
    throw InputError(file, field_path, "expected an array of frames, got " +
                                           std::string(events.type_name()));
  std::vector<HandFrame> frames;
  frames.reserve(events.size());
  for (std::size_t i = 0; i < events.size(); ++i) {
    const std::string path = field_path + "[" + std::to_string(i) + "]";
    HandFrame frame = read_frame(events[i], file, path);
    if (!frames.empty()) detail::check_time_order(frames.back().t, frame.t, file, path + ".t");
    frames.push_back(std::move(frame));
  }
  return frames;
}

namespace detail {

TextLines::TextLines(std::string file) : m_in(file), m_file(std::move(file)) {
  if (!m_in) throw InputError(m_file, "", "cannot open file");
}

bool TextLines::next(std::string& line) {
  if (!std::getline(m_in, line)) return false;
  ++m_number;
  if (!line.empty() && line.back() == '\r') line.pop_back();
  // A byte order mark, which Windows editors put before UTF-8 text, is no part of any of the
  // formats: left in, it hid a JSON Lines header's '{' and the file was taken for a Kinect CSV.
  constexpr std::string_view bom = "\xEF\xBB\xBF";
  if (m_number == 1 && std::string_view(line).substr(0, bom.size()) == bom) line.erase(0, bom.size());
  return true;
}

std::string TextLines::where(const std::string& what) const {
  std::string where = "line " + std::to_string(m_number);
  return what.empty() ? where : where + ": " + what;
}

InputError TextLines::error(const std::string& what, const std::string& message) const {
  return InputError(m_file, where(what), message);
}

std::vector<std::string_view> split_fields(std::string_view line, char separator) {
  std::vector<std::string_view> fields;
  const auto blank = [](char c) { return c == ' ' || c == '\t'; };
  if (separator == ' ') {
    std::size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && blank(line[i])) ++i;
      const std::size_t start = i;
      while (i < line.size() && !blank(line[i])) ++i;
      if (i > start) fields.push_back(line.substr(start, i - start));
    }
    return fields;
  }
  std::size_t start = 0;
  while (true) {
    const std::size_t end = line.find(separator, start);
    std::string_view field = line.substr(start, end == std::string_view::npos ? end : end - start);
    while (!field.empty() && blank(field.front())) field.remove_prefix(1);
    while (!field.empty() && blank(field.back())) field.remove_suffix(1);
    fields.push_back(field);
    if (end == std::string_view::npos) return fields;
    start = end + 1;
  }
}

double parse_finite(std::string_view token, const TextLines& lines, const std::string& what) {
  double value = 0.0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (token.empty() || ec != std::errc() || end != token.data() + token.size())
    throw lines.error(what, "expected a number, got " + quote_text(token));
  if (!std::isfinite(value))
    throw lines.error(what, "must be finite, got " + quote_text(token));
  return value;
}

long long parse_integer(std::string_view token, const TextLines& lines, const std::string& what) {
  long long value = 0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (token.empty() || ec != std::errc() || end != token.data() + token.size())
    throw lines.error(what, "expected an integer, got " + quote_text(token));
  return value;
}

void check_time_order(double previous, double t, const std::string& file,
                      const std::string& field) {
  if (!(t > previous))
    throw InputError(file, field,
                     "time must increase from frame to frame: " + nlohmann::json(t).dump() +
                         " follows " + nlohmann::json(previous).dump());
}

void check_something_to_replay(const Recording& recording, const std::string& file) {
  for (const HandFrame& frame : recording.frames)
    if (frame.left || frame.right || !frame.keys.empty()) return;
  throw InputError(file, "",
                   "no hand tracked and no key in any of the " +
                       std::to_string(recording.frames.size()) + " frames: nothing to replay");
}

}  // namespace detail
}  // namespace drape
