#include "experiments/runner/run_scene.hpp"

#include <fmt/format.h>

#include <optional>

#include "core/parallel/parallel_for.hpp"

#include "experiments/output/event_trace_recorder.hpp"
#include "experiments/output/frame_recorder.hpp"
#include "experiments/output/provenance.hpp"
#include "experiments/output/reference_restarts.hpp"
#include "experiments/output/run_files.hpp"
#include "experiments/output/run_folder.hpp"
#include "experiments/run/scene_simulation.hpp"
#include "experiments/output/series_writers.hpp"
#include "integrators/registry/options_reader.hpp"

namespace drape {

namespace {

nlohmann::json events_json(const Manipulator& manipulator, const Cloth& cloth) {
  nlohmann::json events = nlohmann::json::array();
  for (const ManipulationEvent& e : manipulator.events()) events.push_back(e.to_json(cloth));
  return events;
}

// A cloth that no input drives can only lose energy (gravity is in E, damping removes it):
// E rising above E(0) by more than a stable step's energy error is energy the numerics put in,
// an unstable table or the paper's penetration correction (docs/known_issues.md). 1e-3 of
// E(0) is far above leap-frog's bounded error and below the 3 % of the drape scene's
// energy-gaining tables (docs/integrators/tables-at-large-steps.md).
constexpr double undriven_rise_warning = 1e-3;

nlohmann::json warnings_of(const SceneSimulation& run, double rise_rel) {
  nlohmann::json warnings = nlohmann::json::array();
  if (!run.has_input() && rise_rel > undriven_rise_warning)
    warnings.push_back(fmt::format(
        "the energy rose above its start by {:.3g} |E(0)| with no input driving the cloth: energy "
        "the numerics put in (an unstable step, or the penetration correction)",
        rise_rel));
  return warnings;
}

}  // namespace

nlohmann::json run_summary(const SceneSimulation& run, const EnergyWriter& energy) {
  const Simulation& simulation = run.simulation();
  const Integrator& integrator = simulation.integrator();
  const IntegratorCounters& counters = integrator.counters();
  const ClothSystem& system = run.system();
  const IntegratorOptions& options = run.options();
  const double e0 = energy.initial().total();
  const double rise_rel = energy.rise_max_abs() / std::max(std::abs(e0), 1e-300);
  nlohmann::json summary = {
      {"status", simulation.status().status},
      {"integrator", options.name},
      {"table", options.table},
      {"dt", options.dt},
      {"adaptive", options.adaptive},
      {"steps", counters.steps},
      {"step_mean", counters.steps > 0 ? integrator.time() / static_cast<double>(counters.steps) : 0.0},
      {"step_min", simulation.min_step()},
      {"step_max", simulation.max_step()},
      {"sim_time", integrator.time()},
      {"duration", run.scene().duration},
      {"wall_seconds", simulation.wall_seconds()},
      {"cpu_seconds", simulation.cpu_seconds()},
      {"rhs_evals", counters.rhs_evals},
      {"counters", counters.to_json()},
      {"particles", system.num_particles()},
      {"springs", system.cloth().springs.size()},
      {"object_particles", system.dummy() ? system.dummy()->size() : 0},
      {"threads", thread_count()},
      {"energy_initial", e0},
      {"energy_final", energy.last().total()},
      {"energy_drift_max_abs", energy.drift_max_abs()},
      {"energy_drift_max_rel", energy.drift_max_abs() / std::max(std::abs(e0), 1e-300)},
      {"energy_rise_max_rel", rise_rel},
      {"warnings", warnings_of(run, rise_rel)},
      {"events", events_json(simulation.manipulator(), system.cloth())},
      {"integrator_options", to_json(options)},
      {"scene", run.scene().source},
  };
  if (simulation.status().status != "ok") {
    summary["reason"] = simulation.status().reason;
    summary["time"] = integrator.time();
  }
  return summary;
}

RunOutcome run_scene(const Scene& scene, const std::filesystem::path& out_dir,
                     SimulationObserver* observer) {
  // Taken before the run, so `date` is when it started.
  const nlohmann::json provenance = run_provenance();
  SceneSimulation run(scene);
  return run_scene(run, out_dir, provenance, observer);
}

RunOutcome run_scene(SceneSimulation& run, const std::filesystem::path& out_dir,
                     const nlohmann::json& provenance, SimulationObserver* observer,
                     const std::function<bool()>& keep_going) {
  const Scene& scene = run.scene();
  Simulation& simulation = run.simulation();
  const ClothSystem& system = run.system();
  std::optional<ReferenceRestarts> restarts;
  if (scene.restart_error.enabled()) restarts.emplace(scene);

  // Built (and so validated) first; then no file of an earlier run may stay beside this one's.
  clear_run_folder(out_dir);
  if (system.dummy()) write_dummy_csv(out_dir / "dummy.csv", *system.dummy());
  EnergyWriter energy(out_dir / "energy.csv", scene.output.energy_interval, scene.duration);
  simulation.add_observer(energy);
  std::optional<HandsWriter> hands;
  if (run.has_input()) {
    hands.emplace(out_dir / "hands.csv", scene.output.energy_interval, scene.duration);
    simulation.add_observer(*hands);
  }
  FrameRecorder frames(scene.output, out_dir, system);
  simulation.add_observer(frames);
  EventTraceRecorder event_frames(scene.output, out_dir, system);
  simulation.add_observer(event_frames);
  if (observer) simulation.add_observer(*observer);
  if (restarts) simulation.add_observer(restarts->observer());

  const RunStatus& status = simulation.run(keep_going);
  if (!status.ended())
    return {"interrupted", "stopped at t = " + std::to_string(simulation.time()) + " s",
            exit_failure, {}};
  nlohmann::json summary = run_summary(run, energy);
  summary.update(provenance);
  if (restarts) summary["restart_error"] = restarts->write(out_dir / "restart_error.csv", simulation);
  if (status.status == "ok") write_state_csv(out_dir / "state.csv", system, simulation.state());
  write_json(out_dir / "summary.json", summary);  // last: the folder is complete from here
  const int code = status.status == "ok" ? exit_ok : exit_diverged;
  return {status.status, status.reason, code, std::move(summary)};
}

}  // namespace drape
