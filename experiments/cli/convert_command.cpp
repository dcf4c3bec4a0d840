#include "experiments/cli/convert_command.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "experiments/run/run_scene.hpp"

namespace drape {

RecordingStats recording_stats(const Recording& recording) {
  RecordingStats stats;
  const auto& frames = recording.frames;
  stats.frames = static_cast<int>(frames.size());
  if (frames.size() < 2) return stats;
  stats.duration = frames.back().t - frames.front().t;
  std::vector<double> gaps;
  for (std::size_t i = 1; i < frames.size(); ++i) gaps.push_back(frames[i].t - frames[i - 1].t);
  std::vector<double> sorted = gaps;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(sorted.size() / 2),
                   sorted.end());
  // The median is the sensor's frame interval even when many frames were dropped (Kinect v2:
  // 1/30 s, dropping about 67 ms: docs/input.md).
  stats.frame_interval = sorted[sorted.size() / 2];
  for (const double gap : gaps)
    stats.dropped += std::max(0, static_cast<int>(std::lround(gap / stats.frame_interval)) - 1);
  return stats;
}

int convert_command(const std::string& in, const std::string& out) {
  const Recording recording = read_recording(in);
  write_drapelab_recording(recording, out);
  const RecordingStats s = recording_stats(recording);
  fmt::print("drapelab convert {} -> {}: {} frames, {:.3f} s, frame interval {:.4g} s, "
             "{} dropped frames\n",
             in, out, s.frames, s.duration, s.frame_interval, s.dropped);
  return exit_ok;
}

}  // namespace drape
