#include "experiments/cli/convert_command.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <vector>

#include "core/io/input_error.hpp"
#include "core/io/json_reader.hpp"
#include "core/io/output_error.hpp"
#include "experiments/output/run_files.hpp"
#include "experiments/runner/run_scene.hpp"

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

namespace {

namespace fs = std::filesystem;

// A directory, device or link loop would reach the format detection as "line 0: cannot tell
// the format" or a filesystem exception.
void check_input(const std::string& in) {
  if (const auto reason = unreadable_file_reason(in)) throw InputError(in, "", *reason);
}

// Checked before reading: OUT opened for writing would empty IN when they are one file.
void check_output(const std::string& in, const std::string& out) {
  if (const auto reason = unwritable_file_reason(out))
    throw InputError(out.empty() ? "OUT" : out, "", *reason);
  std::error_code ec;
  if (fs::equivalent(in, out, ec))
    throw InputError(out, "", "is the input recording " + in + ": converting would overwrite it");
  if (fs::is_directory(out, ec)) throw InputError(out, "", "is a directory, not an output file");
  if (ec && ec != std::errc::no_such_file_or_directory) throw InputError(out, "", ec.message());
  const fs::path parent = fs::absolute(out).parent_path();
  if (!fs::is_directory(parent, ec))
    throw InputError(out, "", "its folder " + parent.string() + " does not exist");
  if (const auto reason = open_for_writing_reason(out)) throw InputError(out, "", *reason);
}

}  // namespace

int convert_command(const std::string& in, const std::string& out) {
  check_input(in);
  check_output(in, out);
  const Recording recording = read_recording(in);
  write_drapelab_recording(recording, out);  // OutputError (exit 4) when the write fails
  const RecordingStats s = recording_stats(recording);
  fmt::print("drapelab convert {} -> {}: {} frames, {:.3f} s, frame interval {:.4g} s, "
             "{} dropped frames\n",
             in, out, s.frames, s.duration, s.frame_interval, s.dropped);
  return exit_ok;
}

}  // namespace drape
