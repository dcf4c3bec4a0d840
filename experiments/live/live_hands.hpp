#pragma once
// The hands of a live run driven from the page's pointer or a sensor bridge (docs/live.md, "Live
// hands"): the latest position of each hand, sampled into a growing hand track a little ahead of
// the simulation, so that the track never changes where the simulation has already been and a
// replay of the recorded frames gives the same run.
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "core/input/hand_track.hpp"

namespace drape {

struct HandInput;
struct IntegratorOptions;

/// Live hand samples in the scene frame and scene time, and the track built from them.
class LiveHands {
 public:
  /// Scene time [s] between receiving a hand position and the sample that puts it in the track:
  /// the look-ahead that keeps the track fixed behind the simulation (docs/live.md).
  static constexpr double lead = 0.1;

  /// `keys` are the scene's own keys (scene time); `margin` is the longest step the loop takes
  /// past its target (the integrator's fixed dt).
  LiveHands(TrackPolicy policy, std::vector<HandFrame> keys, double margin);

  /// The latest position of a hand (scene frame); nullopt: the hand is not tracked. Any thread.
  void set(Hand hand, std::optional<HandSample> sample);
  /// A key pressed at scene time t (simulation thread).
  void add_key(double t, const std::string& key);
  /// Simulation thread, between advances at scene time `now`, before advancing towards `wanted`:
  /// adds a frame with the latest hands at `now + lead` (or one spacing after the last frame
  /// when that is not later and the track holds the advance back) and rebuilds `track` from
  /// every frame and key.
  void sample(double now, double wanted, HandTrack& track);
  /// The time the simulation may advance to: before the stretch of the track that the next
  /// sample can still change (+infinity when no hand constrains it).
  double limit() const { return m_limit; }
  /// Why each frame left out of the track so far was (its curve left the scene bound).
  const std::vector<std::string>& left_out() const { return m_left_out; }
  /// Every hand frame and key so far, time-ordered, frames at equal times merged.
  std::vector<HandFrame> recording() const;

 private:
  static std::size_t index(Hand hand) { return hand == Hand::Left ? 0 : 1; }
  /// Whether `frame` has a sample of `hand` that the track uses (the inferred policy).
  bool usable(const HandFrame& frame, Hand hand) const;
  /// The newest frame with a usable sample of `hand` (nullptr: none).
  const HandFrame* last_usable(Hand hand) const;
  double hand_limit(Hand hand, double next_sample) const;

  TrackPolicy m_policy;
  std::vector<HandFrame> m_keys;
  double m_margin;
  std::mutex m_mutex;  ///< guards m_latest
  std::optional<HandSample> m_latest[2];
  std::vector<HandFrame> m_frames;
  /// Per hand (left, right): taken away after it had samples, and not back in a new run yet.
  bool m_gone[2] = {false, false};
  std::vector<std::string> m_left_out;
  int m_refused = 0;  ///< frames left out in a row since the last one taken
  double m_limit = std::numeric_limits<double>::infinity();
};

/// The live hands of a run whose recorded hands give way to live ones (the scene's keys stay, at
/// their scene times), sampled once at t = 0 into `input`'s track; `options` are the run's
/// integrator's (the margin: its fixed dt, 10 ms for an adaptive method).
std::unique_ptr<LiveHands> live_hands_for(HandInput& input, const IntegratorOptions& options);

}  // namespace drape
