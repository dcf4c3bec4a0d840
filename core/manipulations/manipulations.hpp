#pragma once
// The paper's manipulations (section 3; docs/model.md section 7): hold, release, attach and map, any number of
// times in any order. They act between steps, by changing the constraint set and the state;
// the caller restarts its integrator whenever update() reports a change.
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/model/cloth_system.hpp"
#include "core/input/hand_track.hpp"
#include "core/manipulations/hold_search.hpp"
#include "core/manipulations/manipulation_params.hpp"

namespace drape {

namespace detail {
class StateEdit;
}

/// Something that happened (or was refused) at a time, as written to summary.json.
struct ManipulationEvent {
  double t = 0.0;
  std::string type;          ///< hold, release, attach, attach_fixed, map, hold_paused, ignored
  std::string key;           ///< the key that triggered it, "" for holds
  std::string hand;          ///< left, right or ""
  int particle = -1;         ///< cloth particle
  int object_particle = -1;  ///< dummy particle (attach)
  double value = 0.0;        ///< hold: hand distance; attach_fixed: attach error [m]
  std::string reason;        ///< why a key was ignored

  nlohmann::json to_json(const Cloth& cloth) const;
};

/// What one hand is doing: the candidate a viewer colours, and the particle it holds.
struct HandStatus {
  Hand hand;
  bool available = false;
  Vec3 position = Vec3::Zero();
  int candidate = -1;  ///< cloth particle nearest the hand
  double distance = 0.0;
  int held = -1;
};

/// Applies hold, release, attach and map to a ClothSystem from a hand track and its keys.
class Manipulator {
 public:
  /// `track` may be null (no hands; keys only from it otherwise). It must outlive this object.
  Manipulator(ClothSystem& system, const HandTrack* track, const ManipulationParams& params);

  /// Time of the first key, or of the end of a timed attach (attach_time), strictly after t,
  /// or +infinity: callers stop their steps there.
  double next_key_time(double t) const;
  /// Applies everything due at time t (keys, holds, attach countdowns) after a step to state y.
  /// Returns the new state when the constraints or the state changed (restart the integrator).
  std::optional<Eigen::VectorXd> update(double t, const Eigen::VectorXd& y);
  /// Both hands at time t against state y.
  std::vector<HandStatus> hands(double t, const Eigen::VectorXd& y) const;
  const std::vector<ManipulationEvent>& events() const { return m_events; }
  /// At the run's end `t`: records every key not played (pressed after `t`) as ignored, so that
  /// the run's events say which keys of the input it never reached.
  void ignore_keys_after(double t);
  /// Takes over another manipulator's progress (hands, pending attaches, keys applied, events)
  /// on the same scene, so that a branch continues where `other` is (the restart error). The
  /// fixed particles live in the system and are copied with it.
  void copy_state_from(const Manipulator& other);

 private:
  struct HandState {
    Hand hand;
    int held = -1;       ///< cloth particle fixed to this hand
    bool armed = true;   ///< false after a release until the hand has moved away
    bool paused = false; ///< held particle parked while the hand is not tracked
    /// Where the hand let go (release, attach, map); NaN when it was not tracked then.
    Vec3 let_go = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
  };
  struct PendingAttach {
    int particle;
    int object_particle;
    int steps_left;  ///< steps until it is fixed (attach_iterations)
    double due;      ///< time it is fixed (attach_time), or +infinity
  };

  void apply_key(double t, const std::string& key, detail::StateEdit& state, bool& changed);
  void release(double t, const std::string& key, bool& changed);
  void attach(double t, const std::string& key, detail::StateEdit& state, bool& changed);
  void map(double t, const std::string& key, detail::StateEdit& state, bool& changed);
  void update_holds(double t, detail::StateEdit& state, bool& changed);
  /// The hand holds nothing from time t on and must move away before it holds again.
  void let_go(HandState& h, double t) const;
  void finish_attaches(double t, const Eigen::VectorXd& y, bool& changed);
  void add_event(double t, const std::string& type, const std::string& key, const HandState* hand,
                 int particle, int object_particle = -1, double value = 0.0);
  void ignore(double t, const std::string& key, const std::string& reason);
  /// The held particle's trajectory: the hand, reached through a ramp when hold_ramp > 0.
  std::shared_ptr<const Trajectory> hold_trajectory(double t, Hand hand, const Vec3& x,
                                                    const Vec3& v) const;
  /// Whether a hand that holds nothing may take a particle in the next step.
  bool a_hand_may_hold() const;

  ClothSystem& m_system;
  const HandTrack* m_track;
  ManipulationParams m_params;
  std::vector<HandState> m_hands;
  std::vector<PendingAttach> m_attaching;
  std::size_t m_next_key = 0;
  HoldSearch m_hold_search;
  std::vector<ManipulationEvent> m_events;
};

const char* hand_name(Hand hand);

}  // namespace drape
