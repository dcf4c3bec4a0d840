#pragma once
// `drapelab convert IN OUT`: a recording in any format to drapelab JSON Lines, and what it holds
// (frames, duration, dropped frames), so a truncated or gappy recording shows at once.
#include <string>

#include "core/input/recording.hpp"

namespace drape {

/// What a recording holds: its frames, its span and the frames its gaps lost.
struct RecordingStats {
  int frames = 0;
  double duration = 0.0;      ///< last frame's time minus the first's [s]
  double frame_interval = 0.0;  ///< median time between frames [s]
  int dropped = 0;  ///< frames missing from gaps: round(gap / median interval) - 1 per gap
};

/// The stats of a recording's frames (all zero for fewer than two frames).
RecordingStats recording_stats(const Recording& recording);
/// Converts `in` to `out` and prints one line of its stats to stdout; returns the exit status.
int convert_command(const std::string& in, const std::string& out);

}  // namespace drape
