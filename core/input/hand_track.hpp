#pragma once
// The hand track of docs/model.md section 8: recorded hand samples mapped to the scene frame and scene time,
// filtered by an explicit tracking policy, optionally smoothed, and interpolated so that a
// particle held by a hand gets p(t), p'(t) and p''(t) (docs/model.md section 5) at any step size.
// docs/input.md explains each policy and why it was chosen.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/input/recording.hpp"
#include "core/state/state.hpp"

namespace drape {

/// Sensor-to-scene map `scene = scale * R * sensor + translation` (R a rotation, docs/model.md section 8).
struct SensorTransform {
  double scale = 1.0;
  Mat3 rotation = Mat3::Identity();
  Vec3 translation = Vec3::Zero();

  /// A point of the sensor frame in the scene frame.
  Vec3 point(const Vec3& sensor) const { return scale * (rotation * sensor) + translation; }
  /// A velocity or acceleration of the sensor frame in the scene frame.
  Vec3 vector(const Vec3& sensor) const { return scale * (rotation * sensor); }
};

/// Throws an InputError naming `field` unless `r` is a proper rotation (R^T R = I, det R = +1,
/// each to 1e-6): a reflection would turn the right-handed sensor frame into a left-handed one.
void check_rotation(const Mat3& r, const std::string& file, const std::string& field);

/// The farthest a hand may be from the scene's origin in any coordinate [m], recorded or live:
/// no dress form scene is larger than a room, and a stray sensor value must not hold cloth.
constexpr double max_hand_coordinate = 10.0;

/// Throws an InputError naming `field`.x (.y, .z) unless every coordinate of `position` (scene
/// frame) is within +-max_hand_coordinate; NaN fails too.
void check_hand_position(const Vec3& position, const std::string& file, const std::string& field);
/// check_hand_position for every hand sample of `frames` (sensor frame) as `transform` maps it;
/// the field of frame i is `frame_field(i)` + ".left" or ".right".
void check_hand_positions(const std::vector<HandFrame>& frames, const SensorTransform& transform,
                          const std::string& file,
                          const std::function<std::string(std::size_t)>& frame_field);

/// Recording time to scene time: `t_scene = offset + scale * t_recording`.
struct TimeMap {
  double offset = 0.0;
  double scale = 1.0;

  /// Scene time of a recording time.
  double scene(double t_recording) const { return offset + scale * t_recording; }
};

/// What an inferred sample (the sensor guessed the joint from the rest of the body) is worth.
enum class InferredPolicy { Use, Drop };

/// Jitter filter applied to the hand samples before interpolation.
enum class SmoothingFilter { None, OneEuro };

/// One Euro filter (Casiez, Roussel, Vogel, CHI 2012) settings; see docs/input.md for tuning.
struct SmoothingOptions {
  SmoothingFilter filter = SmoothingFilter::None;
  double min_cutoff = 1.0;  ///< Hz: cutoff at rest; lower removes more jitter, adds lag.
  double beta = 0.5;        ///< s/m: cutoff increase per m/s of hand speed; higher, less lag.
  double d_cutoff = 1.0;    ///< Hz: cutoff of the speed estimate that drives the cutoff.
};

/// How samples become a track: which samples count and how far apart they may be bridged.
struct TrackPolicy {
  InferredPolicy inferred = InferredPolicy::Use;
  /// Longest time (recording seconds) between two usable samples that is still interpolated;
  /// 0.15 s bridges up to three missing frames at 30 fps (Kinect drops about 67 ms).
  double max_gap = 0.15;
  SmoothingOptions smoothing;
};

/// Which hand.
enum class Hand { Left, Right };

/// Position, velocity and acceleration of a hand in the scene frame at one time.
struct HandMotion {
  /// True inside a tracked stretch; false means the hand is gone and `position` is where it
  /// was last seen, at rest (velocity and acceleration zero).
  bool available = false;
  Vec3 position = Vec3::Zero();
  Vec3 velocity = Vec3::Zero();
  Vec3 acceleration = Vec3::Zero();
};

/// A key pressed at a scene time.
struct KeyEvent {
  double t = 0.0;
  std::string key;

  bool operator==(const KeyEvent& other) const { return t == other.t && key == other.key; }
};

/// Both hands as C1 cubic Hermite curves over the usable samples, plus the key presses.
class HandTrack {
 public:
  /// A track with no hand samples and no keys.
  HandTrack() = default;
  /// Builds the track from frames in recording time (times strictly increasing).
  HandTrack(const std::vector<HandFrame>& frames, const SensorTransform& transform,
            const TimeMap& time, const TrackPolicy& policy);

  /// Whether the hand is tracked at scene time t (t inside a stretch of bridged samples).
  bool available(Hand hand, double t) const;
  /// The hand at scene time t; nullopt before the hand was first seen.
  std::optional<HandMotion> motion(Hand hand, double t) const;
  /// Key presses in time order (stable for equal times).
  const std::vector<KeyEvent>& keys() const { return m_keys; }
  /// Adds key presses from more frames (recording time, mapped by `time`) and re-sorts.
  void add_keys(const std::vector<HandFrame>& frames, const TimeMap& time);
  /// Scene times of the first and last usable sample of a hand; nullopt if it has none.
  std::optional<std::pair<double, double>> span(Hand hand) const;
  /// Throws InputError(file, field) unless every point of both curves, between the samples too,
  /// has every coordinate within +-max_hand_coordinate: two samples very close in time with
  /// some distance between them give a tangent that throws the curve far away between its
  /// neighbours (1 us apart: 250 m; 2.8e-17 s apart: 3.6e13 m; 5e-324 s apart: NaN).
  void check_curve_bound(const std::string& file, const std::string& field) const;
  /// What check_curve_bound would report, or nullopt when both curves stay within the bound.
  std::optional<std::string> curve_bound_violation() const;
  /// Stretches of a hand's bridged samples, interpolated separately (0 without samples).
  std::size_t runs(Hand hand) const { return curve(hand).run_end.size(); }

 private:
  /// The usable samples of one hand, split into runs that are interpolated separately.
  struct Curve {
    std::vector<double> t;
    std::vector<Vec3> p;
    std::vector<Vec3> m;           ///< Tangent dp/dt at each sample.
    std::vector<std::size_t> run_end;  ///< One past the last sample of each run, increasing.
  };

  static Curve build_curve(const std::vector<double>& t, const std::vector<Vec3>& p,
                           const TrackPolicy& policy);
  const Curve& curve(Hand hand) const { return hand == Hand::Left ? m_left : m_right; }

  Curve m_left;
  Curve m_right;
  std::vector<KeyEvent> m_keys;
};

namespace detail {

/// One Euro filter of a sampled 3-D path (times strictly increasing, recording seconds),
/// restarted by the caller at every run; the speed is the norm of the filtered derivative so
/// that smoothing does not depend on the orientation of the frame.
std::vector<Vec3> one_euro(const std::vector<double>& t, const std::vector<Vec3>& p,
                           const SmoothingOptions& options);

}  // namespace detail
}  // namespace drape
