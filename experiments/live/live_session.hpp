#pragma once
// The live mode's simulation (docs/viewer.md, "Live mode"): one scene stepped in wall-clock time
// through the shared loop on its own thread, keys taken from other threads between steps, and
// each frame published as an immutable snapshot for the server to stream.
#include <atomic>
#include <filesystem>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "core/scene/scene.hpp"

namespace drape {

class SceneSimulation;
class EnergyWriter;
class HandsWriter;
class FrameRecorder;

/// A scene run against the wall clock; the server threads call key() and frame().
class LiveSession {
 public:
  /// Builds the scene (throws InputError like `drapelab run`); writes into out_dir.
  LiveSession(Scene scene, std::filesystem::path out_dir);
  ~LiveSession();

  /// Steps in real time until the scene's duration or stop(); then writes summary.json, the
  /// recording and the replay scene. Returns the summary's status ("ok", "stopped", ...).
  std::string run();
  /// Ends run() at the next frame (from any thread, or a signal handler's watcher).
  void stop() { m_stop = true; }
  bool stopped() const { return m_stop; }
  /// Queues a key ("r", "a", "m"); it is applied at the end of the next step.
  void key(const std::string& key);
  /// The latest frame as a JSON text and its number (0 before the first).
  std::pair<long, std::shared_ptr<const std::string>> frame() const;
  /// Once run() has returned: true.
  bool finished() const { return m_finished; }

 private:
  void publish(double rtf, bool behind);
  void apply_keys();
  void write_outputs(const std::string& status);

  Scene m_scene;
  std::filesystem::path m_out_dir;
  std::unique_ptr<SceneSimulation> m_run;
  std::unique_ptr<EnergyWriter> m_energy;
  std::unique_ptr<HandsWriter> m_hands;
  std::unique_ptr<FrameRecorder> m_frames;
  std::atomic<bool> m_stop{false};
  std::atomic<bool> m_finished{false};
  mutable std::mutex m_mutex;  ///< guards the three members below
  std::vector<std::string> m_pending_keys;
  long m_frame_number = 0;
  std::shared_ptr<const std::string> m_frame;
  std::vector<std::pair<double, std::string>> m_applied_keys;  ///< scene time, key
};

}  // namespace drape
