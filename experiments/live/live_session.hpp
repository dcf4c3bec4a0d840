#pragma once
// The live mode's simulation (docs/live.md): one scene stepped in wall-clock time through the
// shared loop on its own thread, keys and live hands taken from other threads between steps,
// and each frame published as an immutable snapshot for the server to stream.
#include <atomic>
#include <filesystem>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/input/hand_track.hpp"
#include "core/scene/scene.hpp"

namespace drape {

class SceneSimulation;
class EnergyWriter;
class HandsWriter;
class FrameRecorder;
class EventTraceRecorder;
class LiveHands;

/// A scene run against the wall clock; the server threads call key() and frame().
class LiveSession {
 public:
  /// Builds the scene (throws InputError like `drapelab run`), then removes the run files of
  /// out_dir (clear_run_folder; the caller checks it first) and writes into it. The hands
  /// come from the page's pointer and the sensor bridge (live hands) when `live_hands` is set or
  /// the scene has no hand samples of its own; otherwise from the scene's input.
  LiveSession(Scene scene, std::filesystem::path out_dir, bool live_hands);
  ~LiveSession();

  /// Steps in real time until the scene's duration or stop(); then writes summary.json, the
  /// recording and the replay scene. Returns the summary's status ("ok", "stopped", ...).
  std::string run();
  /// Ends run() at the next frame (from any thread, or a signal handler's watcher).
  void stop() { m_stop = true; }
  bool stopped() const { return m_stop; }
  /// Queues a key ("r", "a", "m"); it is applied at the end of the next step.
  void key(const std::string& key);
  /// Whether hand() and sensor_frame() drive the hands.
  bool live_hands() const { return m_live_hands != nullptr; }
  /// A live hand in the scene frame (nullopt: not tracked); only with live_hands(). Throws
  /// InputError naming `source` for a coordinate beyond 10 m.
  void hand(Hand hand, const std::optional<HandSample>& sample, const std::string& source);
  /// A sensor bridge frame (sensor frame, mapped by the scene's input.transform): its hands and
  /// keys; its time is not used, the frame counts when it arrives. Only with live_hands().
  void sensor_frame(const HandFrame& frame, const std::string& source);
  /// What the page needs once: grid, pins, the dress form, whether the hands are live.
  const std::string& scene_json() const { return m_scene_json; }
  /// The latest frame as a JSON text and its number (0 before the first).
  std::pair<long, std::shared_ptr<const std::string>> frame() const;
  /// Every manipulation event published so far (summary.json's form), for a page that missed
  /// some: a frame carries only the last `frame_events` of them.
  nlohmann::json event_log() const;
  /// Events a frame carries at most: the newest, so that a frame's size does not grow with the
  /// run (9000 keys made every frame 814 KB).
  static constexpr std::size_t frame_events = 32;
  /// Once run() has returned: true.
  bool finished() const { return m_finished; }

 private:
  /// Publishes the current frame; `ended` ({status, t, reason}) on the last one, else null.
  void publish(double wall, bool behind, const nlohmann::json& ended = nullptr);
  void apply_keys();
  void write_outputs(const std::string& status);
  bool write_recording(nlohmann::json& scene);

  Scene m_scene;
  std::filesystem::path m_out_dir;
  std::unique_ptr<SceneSimulation> m_run;
  std::unique_ptr<EnergyWriter> m_energy;
  std::unique_ptr<HandsWriter> m_hands;
  std::unique_ptr<FrameRecorder> m_frames;
  std::unique_ptr<EventTraceRecorder> m_event_frames;
  std::unique_ptr<LiveHands> m_live_hands;
  std::size_t m_left_out_reported = 0;  ///< LiveHands::left_out() entries printed so far
  std::string m_scene_json;
  std::atomic<bool> m_stop{false};
  std::atomic<bool> m_finished{false};
  mutable std::mutex m_mutex;  ///< guards the members below
  std::vector<std::string> m_pending_keys;
  long m_frame_number = 0;
  std::shared_ptr<const std::string> m_frame;
  std::vector<std::pair<double, std::string>> m_applied_keys;  ///< scene time, key
  nlohmann::json m_event_log = nlohmann::json::array();  ///< the events published so far
};

}  // namespace drape
