#include "experiments/live/live_session.hpp"

#include <chrono>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <thread>

#include "experiments/run/frame_recorder.hpp"
#include "experiments/run/run_files.hpp"
#include "experiments/run/run_scene.hpp"
#include "experiments/run/scene_simulation.hpp"
#include "experiments/run/series_writers.hpp"

namespace drape {

namespace {

constexpr double frame_interval = 1.0 / 30.0;  // s of wall clock between frames
// Behind the wall clock by more than this [s] is "cannot keep up" (docs/viewer.md, Live mode).
constexpr double behind_tolerance = 0.1;

std::string base64(const void* data, std::size_t size) {
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const auto* b = static_cast<const unsigned char*>(data);
  std::string out;
  out.reserve((size + 2) / 3 * 4);
  for (std::size_t i = 0; i < size; i += 3) {
    const unsigned v = (b[i] << 16) | ((i + 1 < size ? b[i + 1] : 0) << 8) |
                       (i + 2 < size ? b[i + 2] : 0);
    out += table[(v >> 18) & 63];
    out += table[(v >> 12) & 63];
    out += i + 1 < size ? table[(v >> 6) & 63] : '=';
    out += i + 2 < size ? table[v & 63] : '=';
  }
  return out;
}

// A scene without input gets an empty inline one so that live keys have a track to go into;
// the manipulator then sees no hands, as with no input at all.
Scene with_input(Scene scene) {
  if (scene.input.is_null()) {
    scene.input = {{"events", nlohmann::json::array()}};
    scene.source["input"] = scene.input;
  }
  return scene;
}

}  // namespace

LiveSession::LiveSession(Scene scene, std::filesystem::path out_dir)
    : m_scene(with_input(std::move(scene))), m_out_dir(std::move(out_dir)) {
  m_run = std::make_unique<SceneSimulation>(m_scene);
  std::filesystem::create_directories(m_out_dir);
  const ClothSystem& system = m_run->system();
  if (system.dummy()) write_dummy_csv(m_out_dir / "dummy.csv", *system.dummy());
  Simulation& simulation = m_run->simulation();
  m_energy = std::make_unique<EnergyWriter>(m_out_dir / "energy.csv",
                                            m_scene.output.energy_interval, m_scene.duration);
  simulation.add_observer(*m_energy);
  m_hands = std::make_unique<HandsWriter>(m_out_dir / "hands.csv", m_scene.output.energy_interval,
                                          m_scene.duration);
  simulation.add_observer(*m_hands);
  m_frames = std::make_unique<FrameRecorder>(m_scene.output, m_out_dir, system);
  simulation.add_observer(*m_frames);
}

LiveSession::~LiveSession() = default;

void LiveSession::key(const std::string& key) {
  std::lock_guard<std::mutex> lock(m_mutex);
  m_pending_keys.push_back(key);
}

std::pair<long, std::shared_ptr<const std::string>> LiveSession::frame() const {
  std::lock_guard<std::mutex> lock(m_mutex);
  return {m_frame_number, m_frame};
}

void LiveSession::apply_keys() {
  std::vector<std::string> keys;
  {
    std::lock_guard<std::mutex> lock(m_mutex);
    keys.swap(m_pending_keys);
  }
  if (keys.empty()) return;
  // The loop is between steps: a key goes in one step ahead, strictly after time(), so the loop
  // lands on it and applies it there (docs/model.md section 5), as a replay will.
  const Simulation& simulation = m_run->simulation();
  const double step = m_run->options().adaptive ? 1e-3 : m_run->options().dt;
  const double t = simulation.time() + step;
  HandInput& input = *m_run->input();
  std::vector<HandFrame> frames(1);
  frames[0].t = (t - input.config.time.offset) / input.config.time.scale;
  frames[0].keys = keys;
  input.track.add_keys(frames, input.config.time);
  std::lock_guard<std::mutex> lock(m_mutex);
  for (const std::string& k : keys) m_applied_keys.emplace_back(t, k);
}

void LiveSession::publish(double rtf, bool behind) {
  const Simulation& simulation = m_run->simulation();
  const Eigen::VectorXd& y = simulation.state();
  const int n = static_cast<int>(y.size() / 6);
  std::vector<float> positions(3 * static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) positions[3 * i + k] = static_cast<float>(y[6 * i + k]);
  nlohmann::json hands = nlohmann::json::array();
  for (const HandStatus& h : simulation.manipulator().hands(simulation.time(), y))
    hands.push_back({{"hand", h.hand == Hand::Left ? "left" : "right"},
                     {"available", h.available},
                     {"position", {h.position.x(), h.position.y(), h.position.z()}},
                     {"candidate", h.candidate},
                     {"held", h.held}});
  nlohmann::json events = nlohmann::json::array();
  for (const ManipulationEvent& e : simulation.manipulator().events())
    events.push_back(e.to_json(m_run->system().cloth()));
  const nlohmann::json frame = {{"t", simulation.time()},
                                {"rtf", rtf},
                                {"behind", behind},
                                {"rows", m_run->system().cloth().params.rows},
                                {"cols", m_run->system().cloth().params.cols},
                                {"positions", base64(positions.data(), positions.size() * 4)},
                                {"hands", hands},
                                {"events", events}};
  auto text = std::make_shared<const std::string>(frame.dump());
  std::lock_guard<std::mutex> lock(m_mutex);
  m_frame = std::move(text);
  ++m_frame_number;
}

std::string LiveSession::run() {
  using clock = std::chrono::steady_clock;
  Simulation& simulation = m_run->simulation();
  const auto start = clock::now();
  auto next_frame = start;
  bool running = true;
  while (running && !m_stop) {
    apply_keys();
    const double wall = std::chrono::duration<double>(clock::now() - start).count();
    running = simulation.advance(wall);
    const double sim_time = simulation.time();
    const double wall_after = std::chrono::duration<double>(clock::now() - start).count();
    publish(wall_after > 0.0 ? sim_time / wall_after : 1.0,
            sim_time + behind_tolerance < wall_after && !simulation.at_end());
    next_frame += std::chrono::duration_cast<clock::duration>(
        std::chrono::duration<double>(frame_interval));
    std::this_thread::sleep_until(next_frame);
  }
  const std::string status = simulation.status().ended() ? simulation.status().status : "stopped";
  write_outputs(status);
  m_finished = true;
  return status;
}

void LiveSession::write_outputs(const std::string& status) {
  const Simulation& simulation = m_run->simulation();
  if (!simulation.status().ended())  // the loop ended the writers itself otherwise
    for (SimulationObserver* o : std::initializer_list<SimulationObserver*>{
             m_energy.get(), m_hands.get(), m_frames.get()})
      o->on_end(simulation);
  nlohmann::json summary = run_summary(*m_run, *m_energy);
  summary["status"] = status;
  summary["live"] = {{"recording", "recording.jsonl"}, {"replay", "scene.json"}};
  if (status != "diverged" && status != "failed")
    write_state_csv(m_out_dir / "state.csv", m_run->system(), simulation.state());
  write_json(m_out_dir / "summary.json", summary);

  // The live keys in drapelab's recording format with scene times (docs/input.md).
  std::ofstream recording = open_for_writing(m_out_dir / "recording.jsonl");
  nlohmann::json scene = m_scene.source;
  nlohmann::json& events = scene["input"]["events"];
  if (!events.is_array()) events = nlohmann::json::array();
  const TimeMap& time = m_run->input()->config.time;
  for (const auto& [t, k] : m_applied_keys) {
    if (t > simulation.time() + 1e-9) continue;  // queued but never reached
    recording << nlohmann::json({{"t", t}, {"keys", {k}}}).dump() << "\n";
    events.push_back({{"t", (t - time.offset) / time.scale}, {"keys", {k}}});
  }
  // The replay scene: the live scene, its keys inline, ending where the live run stopped.
  scene["duration"] = simulation.time();
  if (scene["input"].contains("recording") && scene["input"]["recording"].is_string())
    scene["input"]["recording"] =
        std::filesystem::absolute(m_scene.base_dir / scene["input"]["recording"].get<std::string>())
            .string();
  write_json(m_out_dir / "scene.json", scene);
}

}  // namespace drape
