#pragma once
// Runs one scene: builds the model, steps it with the chosen integrator, applies the events
// between steps, watches for divergence, and writes the run's files.
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "core/scene/scene.hpp"

#include "experiments/run/simulation.hpp"

namespace drape {

/// Exit statuses of `drapelab` (docs/model.md section 9).
/// drapelab's exit statuses (README.md): exit_output when a run file could not be written
/// (OutputError: a full disk, a quota), the folder then having no summary.json.
enum ExitCode : int {
  exit_ok = 0,
  exit_failure = 1,
  exit_input = 2,
  exit_diverged = 3,
  exit_output = 4
};

/// How a run ended: `ok`, `diverged`, `failed` (a solver could not take a step) or
/// `interrupted` (stopped by its caller before the end; no summary).
struct RunOutcome {
  std::string status;
  std::string reason;
  int exit_code = exit_ok;
  nlohmann::json summary;
};

class SceneSimulation;
class EnergyWriter;
/// summary.json's contents for a run that has ended or been stopped (docs/outputs.md).
nlohmann::json run_summary(const SceneSimulation& run, const EnergyWriter& energy);

/// Runs the scene and writes summary.json, energy.csv and state.csv into out_dir.
/// Throws InputError for invalid input found while building the model. `observer`, if given,
/// watches the run too (an experiment's progress display).
RunOutcome run_scene(const Scene& scene, const std::filesystem::path& out_dir,
                     SimulationObserver* observer = nullptr);
/// run_scene for a run built already and not stepped yet (the Python API's Simulation.run),
/// with the provenance taken when it was asked for. When `keep_going` says no, the run stops
/// between two steps and returns status "interrupted" without summary.json or state.csv: the
/// folder is visibly unfinished (docs/outputs.md).
RunOutcome run_scene(SceneSimulation& run, const std::filesystem::path& out_dir,
                     const nlohmann::json& provenance, SimulationObserver* observer = nullptr,
                     const std::function<bool()>& keep_going = nullptr);

}  // namespace drape
