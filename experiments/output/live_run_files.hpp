#pragma once
// What a live run adds to its folder beside a run's own files (run_file_names; docs/live.md,
// "Replay"): the scene that replays it and its live input as a recording.
#include <string>
#include <vector>

namespace drape {

namespace live_run_file {
inline constexpr const char* replay_scene = "scene.json";
inline constexpr const char* recording = "recording.jsonl";
}  // namespace live_run_file

/// The names above, as a list.
inline const std::vector<std::string>& live_run_file_names() {
  static const std::vector<std::string> names = {live_run_file::replay_scene,
                                                 live_run_file::recording};
  return names;
}

}  // namespace drape
