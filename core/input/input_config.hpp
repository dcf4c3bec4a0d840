#pragma once
// The scene's `input` object (docs/model.md section 8, keys in docs/input.md): which recording, how sensor
// coordinates and times map to the scene, and the tracking policy. Read strictly (unknown keys
// are errors) and written back, so that a run's output folder reproduces its input.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/input/hand_track.hpp"
#include "core/input/recording.hpp"

namespace drape {

/// Everything the scene's `input` object says.
struct InputConfig {
  std::string recording;  ///< Path of the recording file, resolved; empty for none.
  RecordingFormat format = RecordingFormat::Auto;
  std::vector<HandFrame> events;  ///< Inline frames; only keys when a recording is given.
  SensorTransform transform;
  TimeMap time;
  TrackPolicy track;
};

/// Reads `input` (found at `field_path` in `scene_file`); relative recording paths resolve
/// against `base_dir`, the scene file's directory. Errors name the file and the dotted path.
InputConfig parse_input_config(const nlohmann::json& input, const std::string& scene_file,
                               const std::string& field_path,
                               const std::filesystem::path& base_dir);

/// The `input` object that parse_input_config reads back into the same configuration.
nlohmann::json input_config_to_json(const InputConfig& config);

/// The hand input of a scene: its configuration and the track built from it.
struct HandInput {
  InputConfig config;
  std::string source;  ///< The recording's path, "input.events", or empty with no hands.
  HandTrack track;
};

/// Reads the recording (if any) and the inline events and builds the hand track.
HandInput load_hand_input(const InputConfig& config);

/// parse_input_config followed by load_hand_input.
HandInput load_hand_input(const nlohmann::json& input, const std::string& scene_file,
                          const std::string& field_path, const std::filesystem::path& base_dir);

}  // namespace drape
