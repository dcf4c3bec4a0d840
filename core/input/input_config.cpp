#include "core/input/input_config.hpp"

#include "core/io/json_reader.hpp"
#include "core/io/scene_limits.hpp"
#include "core/io/json_text.hpp"

namespace drape {
namespace {

// R as 9 numbers row-major, or as 3 rows of 3: both are common ways of writing a matrix.
Mat3 read_rotation(JsonReader& reader, const std::string& key) {
  const auto& value = reader.raw(key);
  std::vector<double> v;
  const auto bad = [&] {
    return reader.error(key, "expected a 3x3 rotation: 9 numbers row-major or 3 rows of 3, got " +
                                 quote_json(value));
  };
  if (!value.is_array()) throw bad();
  for (const auto& item : value) {
    if (item.is_array() && value.size() == 3 && item.size() == 3) {
      for (const auto& x : item) {
        if (!x.is_number()) throw bad();
        v.push_back(x.get<double>());
      }
    } else if (item.is_number() && value.size() == 9) {
      v.push_back(item.get<double>());
    } else {
      throw bad();
    }
  }
  if (v.size() != 9) throw bad();  // [] has no item to refuse
  Mat3 r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r(i, j) = v[static_cast<std::size_t>(3 * i + j)];
  check_rotation(r, reader.file(), reader.field(key));
  return r;
}

template <class Enum, std::size_t N>
Enum read_choice(JsonReader& reader, const std::string& key, Enum fallback,
                 const std::pair<const char*, Enum> (&choices)[N]) {
  if (!reader.has(key)) return fallback;
  const std::string name = reader.string(key);
  std::string names;
  for (const auto& [choice, value] : choices) {
    if (name == choice) return value;
    names += std::string(names.empty() ? "" : ", ") + "\"" + choice + "\"";
  }
  throw reader.error(key, "expected one of " + names + ", got \"" + name + "\"");
}

constexpr std::pair<const char*, InferredPolicy> inferred_choices[] = {
    {"use", InferredPolicy::Use}, {"drop", InferredPolicy::Drop}};
constexpr std::pair<const char*, SmoothingFilter> filter_choices[] = {
    {"none", SmoothingFilter::None}, {"one-euro", SmoothingFilter::OneEuro}};
constexpr std::pair<const char*, RecordingFormat> format_choices[] = {
    {"auto", RecordingFormat::Auto},
    {"drapelab", RecordingFormat::Drapelab},
    {"kinect-v2-csv", RecordingFormat::KinectV2Csv},
    {"ntu-skeleton", RecordingFormat::NtuSkeleton}};

template <class Enum, std::size_t N>
const char* choice_name(Enum value, const std::pair<const char*, Enum> (&choices)[N]) {
  for (const auto& [name, choice] : choices)
    if (choice == value) return name;
  return choices[0].first;
}

}  // namespace

InputConfig parse_input_config(const nlohmann::json& input, const std::string& scene_file,
                               const std::string& field_path,
                               const std::filesystem::path& base_dir) {
  JsonReader reader(input, scene_file, field_path);
  InputConfig config;
  if (reader.has("recording")) {
    std::filesystem::path path = reader.string("recording");
    if (path.empty()) throw reader.error("recording", "empty path");
    if (path.is_relative()) path = base_dir / path;
    // A directory or a device (/dev/zero) is not "no such file", and reading one would hang.
    if (const auto reason = unreadable_file_reason(path.string()))
      throw reader.error("recording", path.string() + ": " + *reason);
    config.recording = path.lexically_normal().string();
  }
  config.format = read_choice(reader, "format", RecordingFormat::Auto, format_choices);
  if (reader.has("format") && config.recording.empty())
    throw reader.error("format", "only meaningful with input.recording");

  if (reader.has("events")) {
    config.events = read_inline_frames(reader.raw("events"), scene_file, reader.field("events"));
    // One source of hand positions: mixing two clocks and two sensors in one track would
    // invent motion between them.
    if (!config.recording.empty())
      for (std::size_t i = 0; i < config.events.size(); ++i)
        if (config.events[i].left || config.events[i].right)
          throw InputError(scene_file, reader.field("events") + "[" + std::to_string(i) + "]",
                           "hand positions come from input.recording; with a recording, "
                           "events may only add keys");
  }

  if (reader.has("transform")) {
    JsonReader transform = reader.object("transform");
    config.transform.scale = transform.at_most(
        "scale", transform.positive("scale", transform.number("scale", 1.0)), 1e3);
    if (transform.has("rotation")) config.transform.rotation = read_rotation(transform, "rotation");
    config.transform.translation = transform.within(
        "translation", transform.vec3("translation", Vec3::Zero()), limits::max_coordinate);
    transform.finish();
  }
  if (config.recording.empty()) {
    const std::string events = reader.field("events");
    check_hand_positions(config.events, config.transform, scene_file,
                         [&](std::size_t i) { return events + "[" + std::to_string(i) + "]"; });
  }
  config.time.offset = reader.within("time_offset", reader.number("time_offset", 0.0),
                                     limits::max_recording_time);
  config.time.scale = reader.positive("time_scale", reader.number("time_scale", 1.0));
  if (!(config.time.scale >= 1.0 / limits::max_time_scale))
    throw reader.error("time_scale", "must be at least " +
                                         nlohmann::json(1.0 / limits::max_time_scale).dump());
  reader.at_most("time_scale", config.time.scale, limits::max_time_scale);
  config.track.inferred = read_choice(reader, "inferred", InferredPolicy::Use, inferred_choices);
  config.track.max_gap = reader.non_negative("max_gap", reader.number("max_gap", 0.15));
  if (reader.has("smoothing")) {
    JsonReader smoothing = reader.object("smoothing");
    SmoothingOptions& s = config.track.smoothing;
    s.filter = read_choice(smoothing, "filter", SmoothingFilter::None, filter_choices);
    s.min_cutoff = smoothing.positive("min_cutoff", smoothing.number("min_cutoff", s.min_cutoff));
    s.beta = smoothing.non_negative("beta", smoothing.number("beta", s.beta));
    s.d_cutoff = smoothing.positive("d_cutoff", smoothing.number("d_cutoff", s.d_cutoff));
    smoothing.finish();
  }
  reader.finish();
  return config;
}

nlohmann::json input_config_to_json(const InputConfig& config) {
  nlohmann::json out;
  if (!config.recording.empty()) {
    out["recording"] = config.recording;
    out["format"] = choice_name(config.format, format_choices);
  }
  if (!config.events.empty()) {
    out["events"] = nlohmann::json::array();
    for (const auto& frame : config.events)
      out["events"].push_back(nlohmann::json(frame_to_json(frame)));
  }
  const Mat3& r = config.transform.rotation;
  const Vec3& x = config.transform.translation;
  out["transform"] = {
      {"scale", config.transform.scale},
      {"rotation", {{r(0, 0), r(0, 1), r(0, 2)}, {r(1, 0), r(1, 1), r(1, 2)},
                    {r(2, 0), r(2, 1), r(2, 2)}}},
      {"translation", {x.x(), x.y(), x.z()}}};
  out["time_offset"] = config.time.offset;
  out["time_scale"] = config.time.scale;
  out["inferred"] = choice_name(config.track.inferred, inferred_choices);
  out["max_gap"] = config.track.max_gap;
  const SmoothingOptions& s = config.track.smoothing;
  out["smoothing"] = {{"filter", choice_name(s.filter, filter_choices)},
                      {"min_cutoff", s.min_cutoff},
                      {"beta", s.beta},
                      {"d_cutoff", s.d_cutoff}};
  return out;
}

HandInput load_hand_input(const InputConfig& config) {
  HandInput input;
  input.config = config;
  if (!config.recording.empty()) {
    const Recording recording = read_recording(config.recording, config.format);
    check_hand_positions(recording.frames, config.transform, config.recording, [&](std::size_t i) {
      const std::string place = i < recording.frame_places.size() ? recording.frame_places[i] + " " : "";
      return place + "(frame " + std::to_string(i + 1) + ", t = " +
             nlohmann::json(recording.frames[i].t).dump() + " s)";
    });
    input.source = recording.source;
    input.track = HandTrack(recording.frames, config.transform, config.time, config.track);
    input.track.add_keys(config.events, config.time);
  } else if (!config.events.empty()) {
    input.source = "input.events";
    input.track = HandTrack(config.events, config.transform, config.time, config.track);
  }
  return input;
}

HandInput load_hand_input(const nlohmann::json& input, const std::string& scene_file,
                          const std::string& field_path, const std::filesystem::path& base_dir) {
  HandInput loaded = load_hand_input(parse_input_config(input, scene_file, field_path, base_dir));
  const bool recorded = !loaded.config.recording.empty();
  loaded.track.check_curve_bound(recorded ? loaded.config.recording : scene_file,
                                 field_path + (recorded ? ".recording" : ".events"));
  return loaded;
}

}  // namespace drape
