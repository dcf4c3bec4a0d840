#pragma once
// Hand-input recordings (docs/model.md section 8): timestamped frames with the left and right hand positions in
// the sensor frame and the keys pressed. The native format is JSON Lines; the Kinect readers
// (core/input/kinect_readers.hpp) produce the same frames. docs/input.md describes every format.
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/io/input_error.hpp"
#include "core/state/state.hpp"

namespace drape {

/// How the sensor saw a joint (the Kinect TrackingState: 0 not tracked, 1 inferred, 2 tracked).
enum class TrackingState { NotTracked = 0, Inferred = 1, Tracked = 2 };

/// One hand in one frame: its position in the sensor frame and whether it was only inferred.
struct HandSample {
  Vec3 position = Vec3::Zero();
  bool inferred = false;

  bool operator==(const HandSample& other) const {
    return position == other.position && inferred == other.inferred;
  }
};

/// One timestamped frame; an absent hand was not tracked in that frame.
struct HandFrame {
  double t = 0.0;
  std::optional<HandSample> left;
  std::optional<HandSample> right;
  std::vector<std::string> keys;

  bool operator==(const HandFrame& other) const {
    return t == other.t && left == other.left && right == other.right && keys == other.keys;
  }
};

/// A sequence of frames with strictly increasing times, and where they came from.
struct Recording {
  std::string source;
  std::vector<HandFrame> frames;
  /// Where each frame is in the file ("line 12", "lines 30-80"), for errors found after
  /// reading (a hand outside the scene once transformed); empty when not read from a file.
  std::vector<std::string> frame_places;
};

/// The keys a frame may press, each bound to a manipulation (docs/manipulations.md): r release,
/// a attach, m map. Any other is an error where frames are read: it would do nothing, silently.
const std::vector<std::string>& manipulation_keys();

/// The file formats a recording can be read from.
enum class RecordingFormat { Auto, Drapelab, KinectV2Csv, NtuSkeleton };

/// Format of a file from its content (first non-blank line); throws InputError if unknown.
RecordingFormat detect_recording_format(const std::string& file);

/// Reads a native drapelab JSON Lines recording.
Recording read_drapelab_recording(const std::string& file);
/// Checks the header line of the native JSON Lines format ({"format": "drapelab-recording",
/// "version": 1}); errors name `file` and `where`. The sensor bridge checks a header that opens
/// its stream with it.
void read_drapelab_header_line(const std::string& line, const std::string& file,
                               const std::string& where);
/// One frame line of the native JSON Lines format (after the header), as read_drapelab_recording
/// reads it; errors name `file` and `where` (e.g. "line 3"). The live mode's sensor bridge reads
/// its stream with it (docs/live.md).
HandFrame read_drapelab_frame_line(const std::string& line, const std::string& file,
                                   const std::string& where);
/// Writes a recording as native JSON Lines (round-trip precision); throws OutputError on failure.
void write_drapelab_recording(const Recording& recording, const std::string& file);
/// Reads a recording in any supported format (Auto: detected from the content).
Recording read_recording(const std::string& file, RecordingFormat format = RecordingFormat::Auto);
/// Reads a recording in any format and writes it as native JSON Lines (`drapelab convert`).
void convert_recording(const std::string& in, const std::string& out);

/// Frames given inline as a JSON array (`input.events`); errors name `field_path[i].key`.
std::vector<HandFrame> read_inline_frames(const nlohmann::json& events, const std::string& file,
                                          const std::string& field_path);
/// One frame as a JSON object of the native format (null hands written explicitly).
nlohmann::ordered_json frame_to_json(const HandFrame& frame);

namespace detail {

/// A text file read line by line, so that every error can name its line.
class TextLines {
 public:
  /// Opens `file`; throws InputError if it cannot be read.
  explicit TextLines(std::string file);
  /// Reads the next line (without '\n' or a trailing '\r', and the first line without a UTF-8
  /// byte order mark); false at the end of the file.
  bool next(std::string& line);
  /// 1-based number of the line last read.
  int number() const { return m_number; }
  const std::string& file() const { return m_file; }
  /// "line N", or "line N: what" when `what` names a field of the line.
  std::string where(const std::string& what = "") const;
  /// An InputError about the current line.
  InputError error(const std::string& what, const std::string& message) const;

 private:
  std::ifstream m_in;
  std::string m_file;
  int m_number = 0;
};

/// Splits a line at `separator`; with ' ' any run of blanks separates and ends are trimmed.
std::vector<std::string_view> split_fields(std::string_view line, char separator);
/// A finite floating-point number, or an InputError naming the line and `what`.
double parse_finite(std::string_view token, const TextLines& lines, const std::string& what);
/// An integer, or an InputError naming the line and `what`.
long long parse_integer(std::string_view token, const TextLines& lines, const std::string& what);
/// Throws an InputError naming `field` unless `t` is later than `previous` (interpolation
/// needs distinct knots, so equal times are rejected as well as time going backwards).
void check_time_order(double previous, double t, const std::string& file,
                      const std::string& field);
/// Throws an InputError unless some frame of `recording` has a hand or a key: a replay
/// without either runs as if nothing were wrong and never holds anything.
void check_something_to_replay(const Recording& recording, const std::string& file);

}  // namespace detail
}  // namespace drape
