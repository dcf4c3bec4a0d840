#pragma once
// A scene stepped under a program's control (the Python API, docs/python.md): the run of
// `drapelab run` advanced to any time in pieces, with keys pressed and, with live hands, hand
// positions set between advances, as the live page does (docs/live.md). Knows nothing of Python.
#include <Eigen/Core>
#include <filesystem>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/input/hand_track.hpp"
#include "core/scene/scene.hpp"
#include "experiments/runner/run_scene.hpp"

namespace drape {

class SceneSimulation;
class LiveHands;

/// One scene's simulation, driven step by step from a program.
class InteractiveSimulation {
 public:
  /// Builds the scene as `drapelab run` does (throws InputError the same way). With
  /// `live_hands`, set_hand() drives the hands instead of the scene's recorded ones (its keys
  /// stay), as `drapelab live --live-hands` does.
  InteractiveSimulation(const Scene& scene, bool live_hands);
  ~InteractiveSimulation();
  InteractiveSimulation(const InteractiveSimulation&) = delete;
  InteractiveSimulation& operator=(const InteractiveSimulation&) = delete;

  /// Steps until simulated time t (events applied on the way), the end, or until `keep_going`
  /// (asked between steps) says no: a pause that changes no step. False once the run has ended.
  bool advance(double t, const std::function<bool()>& keep_going = nullptr);
  /// One step; false once the run has ended.
  bool step(const std::function<bool()>& keep_going = nullptr);
  /// Presses "r", "a" or "m": it goes into the track one step ahead, where the loop applies it
  /// (docs/model.md section 5), as a key of the live page does. InputError for another key or a
  /// scene without input (and no live hands).
  void press(const std::string& key);
  /// A live hand at `position` (scene frame) from now on; nullopt: not tracked. InputError
  /// without live hands or beyond the hands' bound (NaN included).
  void set_hand(Hand hand, const std::optional<Vec3>& position);
  /// The cloth particle the hand would take now (-1: no hand there).
  int hold_candidate(Hand hand) const;
  /// Sets the positions (first half) or velocities (second half) of the state at time(), then
  /// projects it and restarts the integrator there (Simulation::set_state).
  void set_block(bool velocities, const Eigen::Ref<const Eigen::VectorXd>& values);
  /// Runs the whole scene into `out_dir` as `drapelab run` does (same files, same bytes).
  /// Only before the first step and without live hands; InputError otherwise.
  RunOutcome run_to_folder(const std::filesystem::path& out_dir, bool overwrite,
                           const std::function<bool()>& keep_going);
  /// Writes the live hands and keys so far as a drapelab recording (JSON Lines) and returns the
  /// scene that replays them up to time() (docs/live.md, the replay). Only with live hands.
  nlohmann::json write_recording(const std::filesystem::path& file) const;

  const SceneSimulation& run() const { return *m_run; }
  const Simulation& simulation() const;
  bool live_hands() const { return m_live_hands != nullptr; }

 private:
  Scene m_scene;
  std::unique_ptr<SceneSimulation> m_run;
  std::unique_ptr<LiveHands> m_live_hands;
  bool m_started = false;
  bool m_hands_set = false;  ///< set_hand() was called since the last sample of the live hands
};

}  // namespace drape
