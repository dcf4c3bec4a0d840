#include "experiments/python/interactive_simulation.hpp"

#include <cmath>
#include <limits>

#include "core/dummy/dummy_sources.hpp"
#include "core/input/input_config.hpp"
#include "core/io/input_error.hpp"
#include "experiments/live/live_hands.hpp"
#include "experiments/output/provenance.hpp"
#include "experiments/output/run_folder.hpp"
#include "experiments/run/scene_simulation.hpp"

namespace drape {

namespace {

// With live hands the keys and hands need a track to go into: a scene without input gets an
// empty inline one, as in the live mode (experiments/live/live_session.cpp).
Scene prepared(Scene scene, bool live_hands) {
  if (live_hands && scene.input.is_null()) {
    scene.input = {{"events", nlohmann::json::array()}};
    scene.source["input"] = scene.input;
  }
  return scene;
}

}  // namespace

InteractiveSimulation::InteractiveSimulation(const Scene& scene, bool live_hands)
    : m_scene(prepared(scene, live_hands)),
      m_run(std::make_unique<SceneSimulation>(m_scene)) {
  // The scene's keys stay (at their scene times); its recorded hands give way to set_hand().
  if (live_hands) m_live_hands = live_hands_for(*m_run->input(), m_run->options());
}

InteractiveSimulation::~InteractiveSimulation() = default;

const Simulation& InteractiveSimulation::simulation() const { return m_run->simulation(); }

bool InteractiveSimulation::advance(double t, const std::function<bool()>& keep_going) {
  m_started = true;
  Simulation& simulation = m_run->simulation();
  bool paused = false;
  const auto asked = [&] {
    paused = keep_going && !keep_going();
    return !paused;
  };
  for (bool held_back = false;; held_back = true) {
    double target = t;
    if (m_live_hands) {
      // As the live loop does each turn: the latest hands sampled ahead, the advance held
      // before the stretch of the track that the next sample can still change. A turn here is
      // a hand set (a sample each step would make the track a staircase of 0.2 ms frames) or
      // an advance the track holds back (a sample moves its limit on).
      if (m_hands_set || held_back) m_live_hands->sample(simulation.time(), t, m_run->input()->track);
      m_hands_set = false;
      target = std::min(t, m_live_hands->limit());
    }
    const bool running = simulation.advance(target, asked);
    if (!running || paused || target >= t || simulation.at_end()) return running;
  }
}

bool InteractiveSimulation::step(const std::function<bool()>& keep_going) {
  long steps = 0;
  return advance(std::numeric_limits<double>::infinity(),
                 [&] { return steps++ == 0 && (!keep_going || keep_going()); });
}

void InteractiveSimulation::press(const std::string& key) {
  if (key != "r" && key != "a" && key != "m")
    throw InputError("Simulation.press", "key",
                     "'" + shorten(key) + "' is not a key: r (release), a (attach) or m (map)");
  HandInput* input = m_run->input();
  if (input == nullptr)
    throw InputError("Simulation.press", "key",
                     "the scene has no input to take keys: Simulation(scene, live_hands=True) "
                     "gives it one");
  // Between steps: the key goes in one step ahead, strictly after time(), so that the loop
  // lands on it and applies it there (docs/model.md section 5), as the live page's keys do.
  const double step = m_run->options().adaptive ? 1e-3 : m_run->options().dt;
  const double t = m_run->simulation().time() + step;
  std::vector<HandFrame> frames(1);
  frames[0].keys = {key};
  if (m_live_hands) {
    m_live_hands->add_key(t, key);
    frames[0].t = t;
    input->track.add_keys(frames, TimeMap{});
  } else {
    frames[0].t = (t - input->config.time.offset) / input->config.time.scale;
    input->track.add_keys(frames, input->config.time);
  }
}

void InteractiveSimulation::set_hand(Hand hand, const std::optional<Vec3>& position) {
  if (!m_live_hands)
    throw InputError("Simulation.set_hand", hand_name(hand),
                     "the scene's recorded hands drive this simulation: "
                     "Simulation(scene, live_hands=True) takes hands from set_hand");
  if (position) check_hand_position(*position, "Simulation.set_hand", hand_name(hand));
  m_live_hands->set(hand, position ? std::optional<HandSample>(HandSample{*position, false})
                                   : std::nullopt);
  m_hands_set = true;
}

int InteractiveSimulation::hold_candidate(Hand hand) const {
  const Simulation& simulation = m_run->simulation();
  for (const HandStatus& h : simulation.manipulator().hands(simulation.time(), simulation.state()))
    if (h.hand == hand && h.available) return h.candidate;
  return -1;
}

void InteractiveSimulation::set_block(bool velocities, const Eigen::Ref<const Eigen::VectorXd>& values) {
  Simulation& simulation = m_run->simulation();
  Eigen::VectorXd y = simulation.state();
  const Eigen::Index n3 = y.size() / 2;
  if (values.size() != n3 || !values.allFinite())
    throw InputError("Simulation", velocities ? "velocities" : "positions",
                     "expected " + std::to_string(n3 / 3) + " finite rows of 3");
  y.segment(velocities ? n3 : 0, n3) = values;
  simulation.set_state(std::move(y));
}

RunOutcome InteractiveSimulation::run_to_folder(const std::filesystem::path& out_dir,
                                                bool overwrite,
                                                const std::function<bool()>& keep_going) {
  if (m_started || m_live_hands)
    throw InputError("Simulation.run", "out_dir",
                     "writes drapelab run's folder from the scene's start: call it on a new "
                     "Simulation(scene) that has not stepped, without live hands");
  check_run_folder(out_dir, overwrite);
  check_run_folder_not_experiment(out_dir);
  const nlohmann::json provenance = run_provenance();
  m_started = true;
  return run_scene(*m_run, out_dir, provenance, nullptr, keep_going);
}

nlohmann::json InteractiveSimulation::write_recording(const std::filesystem::path& file) const {
  if (!m_live_hands)
    throw InputError("Simulation.write_recording", "file",
                     "only a Simulation(scene, live_hands=True) records its hands");
  const std::filesystem::path path = std::filesystem::absolute(file);
  Recording recording{path.string(), {}, {}};
  for (const HandFrame& frame : m_live_hands->recording())
    if (frame.left || frame.right || !frame.keys.empty()) recording.frames.push_back(frame);
  write_drapelab_recording(recording, path.string());
  // The replay scene of the live mode (live_session.cpp): the recording as its input in scene
  // frame and time, ending where this simulation is.
  InputConfig replay = m_run->input()->config;
  replay.recording = path.string();
  replay.format = RecordingFormat::Drapelab;
  replay.events.clear();
  replay.transform = SensorTransform{};
  replay.time = TimeMap{};
  nlohmann::json scene = m_scene.source;
  if (scene.contains("dummy")) make_dummy_paths_absolute(scene["dummy"], m_scene.base_dir);
  scene["input"] = input_config_to_json(replay);
  scene["duration"] = simulation().time();
  scene["runaway_horizon"] = m_scene.runaway_horizon;
  return scene;
}

}  // namespace drape
