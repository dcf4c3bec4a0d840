#include "experiments/live/live_session.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <thread>

#include "core/dummy/dummy_sources.hpp"
#include "core/input/input_config.hpp"
#include "core/io/input_error.hpp"
#include "experiments/live/live_hands.hpp"
#include "experiments/output/live_run_files.hpp"
#include "experiments/output/event_trace_recorder.hpp"
#include "experiments/output/frame_recorder.hpp"
#include "experiments/output/run_folder.hpp"
#include "experiments/output/run_files.hpp"
#include "experiments/runner/run_scene.hpp"
#include "experiments/run/scene_simulation.hpp"
#include "experiments/output/series_writers.hpp"
#include "experiments/viewer/page_data.hpp"

namespace drape {

namespace {

constexpr double frame_interval = 1.0 / 30.0;  // s of wall clock between frames

// Merges key frames (scene times) into a scene's input.events, mapped back to recording time:
// each at its place in time, its keys joining an event at the same time, since the events'
// times must increase (docs/input.md); appended at the end they broke the replay of every
// scene whose events went on past a live key.
void add_events(nlohmann::json& input, const std::vector<HandFrame>& key_frames,
                const TimeMap& time) {
  nlohmann::json& events = input["events"];
  if (!events.is_array()) events = nlohmann::json::array();
  for (const HandFrame& frame : key_frames) {
    const double t = (frame.t - time.offset) / time.scale;
    auto at = std::find_if(events.begin(), events.end(),
                           [&](const nlohmann::json& e) { return e.at("t").get<double>() >= t; });
    if (at != events.end() && at->at("t").get<double>() == t) {
      nlohmann::json& keys = (*at)["keys"];
      if (!keys.is_array()) keys = nlohmann::json::array();
      for (const std::string& k : frame.keys) keys.push_back(k);
    } else {
      nlohmann::json event = {{"t", t}, {"keys", frame.keys}};
      events.insert(at, std::move(event));
    }
  }
}
// Behind the wall clock by more than this [s] is "cannot keep up" (docs/live.md).
constexpr double behind_tolerance = 0.1;

// A scene without input gets an empty inline one so that live keys have a track to go into;
// the manipulator then sees no hands, as with no input at all.
Scene with_input(Scene scene) {
  if (scene.input.is_null()) {
    scene.input = {{"events", nlohmann::json::array()}};
    scene.source["input"] = scene.input;
  }
  return scene;
}

bool has_hand_samples(const HandTrack& track) {
  return track.span(Hand::Left) || track.span(Hand::Right);
}

// The grid, the pins and the dress form for the page's 3-D scene (viewer_scene.js), once.
std::string page_scene_json(const ClothSystem& system, const Scene& scene, bool live_hands) {
  nlohmann::json pins = nlohmann::json::array();
  for (const GridPoint& p : scene.pins) pins.push_back({p.row, p.col});
  const Dummy* d = system.dummy();
  std::vector<double> positions;
  for (int o = 0; d && o < d->size(); ++o)
    for (int k = 0; k < 3; ++k) positions.push_back(d->position(o)[k]);
  return nlohmann::json({{"rows", system.cloth().params.rows},
                         {"cols", system.cloth().params.cols},
                         {"pins", pins},
                         {"dummy", dummy_page_json(d ? d->num_sections() : 0, d ? d->points() : 0,
                                                   positions)},
                         // The markers' size: the grid's rest spacing, not the first frame's
                         // particle distance (a stretched cloth, docs/live.md).
                         {"spacing", system.cloth().params.spacing},
                         {"live_hands", live_hands},
                         {"duration", scene.duration}})
      .dump();
}

// The bound of recorded hands (core/input/hand_track.hpp), for a pointer or sensor value.
void check_hand(Hand hand, const std::optional<HandSample>& sample, const std::string& source) {
  if (sample) check_hand_position(sample->position, source, hand == Hand::Left ? "left" : "right");
}

}  // namespace

LiveSession::LiveSession(Scene scene, std::filesystem::path out_dir, bool live_hands)
    : m_scene(with_input(std::move(scene))), m_out_dir(std::move(out_dir)) {
  // A live session has no reference to branch and is watched, not measured (docs/live.md).
  if (m_scene.restart_error.enabled())
    throw InputError(m_scene.file, "restart_error",
                     "is measured by drapelab run and experiments, not in a live session");
  m_run = std::make_unique<SceneSimulation>(m_scene);
  HandInput& input = *m_run->input();
  // The scene's keys stay (at their scene times); its recorded hands, if any, give way.
  if (live_hands || !has_hand_samples(input.track))
    m_live_hands = live_hands_for(input, m_run->options());
  m_scene_json = page_scene_json(m_run->system(), m_scene, m_live_hands != nullptr);
  // Built (and so validated) first; then no file of an earlier run may stay beside this one's.
  clear_run_folder(m_out_dir);
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
  m_event_frames = std::make_unique<EventTraceRecorder>(m_scene.output, m_out_dir, system);
  simulation.add_observer(*m_event_frames);
}

LiveSession::~LiveSession() = default;

void LiveSession::hand(Hand hand, const std::optional<HandSample>& sample,
                       const std::string& source) {
  check_hand(hand, sample, source);
  if (m_live_hands) m_live_hands->set(hand, sample);
}

void LiveSession::sensor_frame(const HandFrame& frame, const std::string& source) {
  const SensorTransform& transform = m_run->input()->config.transform;
  std::optional<HandSample> left = frame.left, right = frame.right;
  if (left) left->position = transform.point(left->position);
  if (right) right->position = transform.point(right->position);
  // Both checked before either is used: a frame counts whole or not at all.
  check_hand(Hand::Left, left, source);
  check_hand(Hand::Right, right, source);
  hand(Hand::Left, left, source);
  hand(Hand::Right, right, source);
  for (const std::string& k : frame.keys) key(k);
}

void LiveSession::key(const std::string& key) {
  std::lock_guard<std::mutex> lock(m_mutex);
  m_pending_keys.push_back(key);
}

std::pair<long, std::shared_ptr<const std::string>> LiveSession::frame() const {
  std::lock_guard<std::mutex> lock(m_mutex);
  return {m_frame_number, m_frame};
}

nlohmann::json LiveSession::event_log() const {
  std::lock_guard<std::mutex> lock(m_mutex);
  return m_event_log;
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
  frames[0].keys = keys;
  if (m_live_hands) {
    // In the track at once and at every rebuild (sample()), which starts from LiveHands' keys.
    for (const std::string& k : keys) m_live_hands->add_key(t, k);
    frames[0].t = t;
    input.track.add_keys(frames, TimeMap{});
  } else {
    frames[0].t = (t - input.config.time.offset) / input.config.time.scale;
    input.track.add_keys(frames, input.config.time);
  }
  std::lock_guard<std::mutex> lock(m_mutex);
  for (const std::string& k : keys) m_applied_keys.emplace_back(t, k);
}

void LiveSession::publish(double wall, bool behind, const nlohmann::json& ended) {
  const Simulation& simulation = m_run->simulation();
  const Eigen::VectorXd& y = simulation.state();
  // y = [x; v] (core/state/state.hpp): the first 3N values are the positions.
  std::vector<float> positions(static_cast<std::size_t>(y.size() / 2));
  for (std::size_t i = 0; i < positions.size(); ++i)
    positions[i] = static_cast<float>(y[static_cast<Eigen::Index>(i)]);
  // Little-endian float32, as JavaScript's Float32Array reads it on every browser platform.
  const auto* bytes = reinterpret_cast<const unsigned char*>(positions.data());
  nlohmann::json hands = nlohmann::json::array();
  for (const HandStatus& h : simulation.manipulator().hands(simulation.time(), y))
    hands.push_back({{"hand", h.hand == Hand::Left ? "left" : "right"},
                     {"available", h.available},
                     {"position", {h.position.x(), h.position.y(), h.position.z()}},
                     {"candidate", h.candidate},
                     {"held", h.held}});
  // The manipulator's events only grow: the new ones join the log, and the frame carries the
  // newest frame_events with the index of the first (the page fetches /event-log for a gap).
  const std::vector<ManipulationEvent>& all = simulation.manipulator().events();
  const std::size_t logged = m_event_log.size();  // only this thread appends
  nlohmann::json fresh = nlohmann::json::array();
  for (std::size_t k = logged; k < all.size(); ++k)
    fresh.push_back(all[k].to_json(m_run->system().cloth()));
  const std::size_t first = all.size() > frame_events ? all.size() - frame_events : 0;
  nlohmann::json events = nlohmann::json::array();
  for (std::size_t k = first; k < all.size(); ++k)
    events.push_back(k < logged ? m_event_log[k] : fresh[k - logged]);
  const nlohmann::json frame = {{"t", simulation.time()},
                                {"wall", wall},
                                {"rtf", wall > 0.0 ? simulation.time() / wall : 1.0},
                                {"behind", behind},
                                {"rows", m_run->system().cloth().params.rows},
                                {"cols", m_run->system().cloth().params.cols},
                                {"positions", base64_encode(bytes, positions.size() * sizeof(float))},
                                {"fixed", m_run->system().constraints().fixed_particles()},
                                {"hands", hands},
                                {"event_count", all.size()},
                                {"events_from", first},
                                {"events", events},
                                {"ended", ended}};
  auto text = std::make_shared<const std::string>(frame.dump());
  std::lock_guard<std::mutex> lock(m_mutex);
  for (auto& e : fresh) m_event_log.push_back(std::move(e));
  m_frame = std::move(text);
  ++m_frame_number;
}

std::string LiveSession::run() {
  // However the run ends (its end, a stop, a write that failed and threw), the page's stream
  // and the command waiting for the session end with it.
  struct Finish {
    std::atomic<bool>& finished;
    ~Finish() { finished = true; }
  } finish{m_finished};
  using clock = std::chrono::steady_clock;
  Simulation& simulation = m_run->simulation();
  const auto start = clock::now();
  auto next_frame = start;
  bool running = true;
  while (running && !m_stop) {
    apply_keys();
    const double wall = std::chrono::duration<double>(clock::now() - start).count();
    // To the wall clock: a run that fell behind (a stall at the start, a busy machine) and can
    // step faster than real time catches up, as fast as the turn's wall time below allows; with
    // at most one frame interval a turn it stayed behind by the stall for good, showing "cannot
    // keep up" beside a real-time factor of 1.00. The turn's wall-time bound, not this target,
    // is what keeps a slow run publishing, taking keys and stopping on SIGINT every turn.
    double target = wall;
    if (m_live_hands) {
      m_live_hands->sample(simulation.time(), target, m_run->input()->track);
      const auto& left_out = m_live_hands->left_out();
      for (; m_left_out_reported < left_out.size(); ++m_left_out_reported)
        fmt::print(stderr, "drapelab live: hand frame at {}: left out\n",
                   left_out[m_left_out_reported]);
      target = std::min(target, m_live_hands->limit());
    }
    // Within the turn's wall time: a slow step rate (a large cloth, an adaptive method taking
    // small steps) still publishes, takes keys and stops on SIGINT every turn or so; it kept
    // Ctrl-C waiting for minutes while it stepped through its 1/30 s of simulated time.
    const auto turn_end = next_frame + std::chrono::duration_cast<clock::duration>(
                                           std::chrono::duration<double>(frame_interval));
    running = simulation.advance(target, [&] { return !m_stop && clock::now() < turn_end; });
    const double sim_time = simulation.time();
    const double wall_after = std::chrono::duration<double>(clock::now() - start).count();
    publish(wall_after, sim_time + behind_tolerance < wall_after && !simulation.at_end());
    next_frame += std::chrono::duration_cast<clock::duration>(
        std::chrono::duration<double>(frame_interval));
    std::this_thread::sleep_until(next_frame);
  }
  // Keys taken after the last turn (Ctrl-C right after them) go in a step past the end: listed
  // as ignored, as the replay, which ends there, lists them (a run that diverged or failed
  // lists no key after its end, nor does its replay).
  apply_keys();
  if (!simulation.status().ended() || simulation.status().status == "ok")
    simulation.list_unplayed_keys();
  const std::string status = simulation.status().ended() ? simulation.status().status : "stopped";
  // The stream's last frame says that the run ended, when and why: the page shows it (a page
  // left open otherwise reads as a run still going; docs/live.md, The page).
  publish(std::chrono::duration<double>(clock::now() - start).count(), false,
          {{"status", status}, {"t", simulation.time()}, {"reason", simulation.status().reason}});
  write_outputs(status);
  return status;
}

void LiveSession::write_outputs(const std::string& status) {
  const Simulation& simulation = m_run->simulation();
  if (!simulation.status().ended())  // the loop ended the writers itself otherwise
    for (SimulationObserver* o : std::initializer_list<SimulationObserver*>{
             m_energy.get(), m_hands.get(), m_frames.get(), m_event_frames.get()})
      o->on_end(simulation);
  if (status != "diverged" && status != "failed")
    write_state_csv(m_out_dir / "state.csv", m_run->system(), simulation.state());
  nlohmann::json scene = m_scene.source;
  // The replay scene lives in DIR: file names relative to the live scene's folder are made
  // absolute (a relative dummy.mesh was not found by the replay).
  if (scene.contains("dummy")) make_dummy_paths_absolute(scene["dummy"], m_scene.base_dir);
  const bool recorded = write_recording(scene);
  // The replay scene: the live scene, its keys inline, ending where the live run stopped, with
  // the live run's runaway bound (a shorter duration would shrink it: the replay could diverge
  // where the live run did not, or earlier).
  scene["duration"] = simulation.time();
  scene["runaway_horizon"] = m_scene.runaway_horizon;
  write_json(m_out_dir / live_run_file::replay_scene, scene);
  // summary.json last: a folder is complete only when it exists (docs/outputs.md), so a write
  // that fails before it leaves no folder that looks finished.
  nlohmann::json summary = run_summary(*m_run, *m_energy);
  summary["status"] = status;
  summary["live"] = {
      {"recording", recorded ? nlohmann::json(live_run_file::recording) : nlohmann::json()},
      {"replay", live_run_file::replay_scene},
      {"hands", m_live_hands ? "live" : "scene"},
      {"hand_frames_left_out", m_live_hands ? m_live_hands->left_out().size() : 0}};
  write_json(m_out_dir / "summary.json", summary);
}

// recording.jsonl: the live input in drapelab's recording format, scene times (docs/live.md).
// With live hands the replay scene plays it as its input.recording; otherwise the scene keeps
// its own input and gets the live keys merged into input.events in time order. A session with
// no input at all writes no recording (drapelab's reader refuses a file without frames), and
// its replay scene has no hand input; returns whether it wrote one.
bool LiveSession::write_recording(nlohmann::json& scene) {
  const std::filesystem::path file = std::filesystem::absolute(m_out_dir / live_run_file::recording);
  const InputConfig& config = m_run->input()->config;
  Recording recording{file.string(), {}, {}};
  if (m_live_hands) {
    // Frames past the end stay: the track had their hands when it interpolated before it, and
    // their keys are the ones the run listed as ignored.
    for (const HandFrame& frame : m_live_hands->recording())
      if (frame.left || frame.right || !frame.keys.empty()) recording.frames.push_back(frame);
    InputConfig replay = config;
    replay.recording = recording.frames.empty() ? "" : file.string();
    replay.format = RecordingFormat::Drapelab;
    replay.events.clear();
    replay.transform = SensorTransform{};
    replay.time = TimeMap{};
    scene["input"] = input_config_to_json(replay);
  } else {
    for (const auto& [t, k] : m_applied_keys) {
      if (recording.frames.empty() || recording.frames.back().t != t)
        recording.frames.push_back(HandFrame{t, std::nullopt, std::nullopt, {}});
      recording.frames.back().keys.push_back(k);
    }
    add_events(scene["input"], recording.frames, config.time);
    if (scene["input"].contains("recording") && scene["input"]["recording"].is_string())
      scene["input"]["recording"] = std::filesystem::absolute(config.recording).string();
  }
  if (recording.frames.empty()) return false;
  write_drapelab_recording(recording, file.string());
  return true;
}

}  // namespace drape
