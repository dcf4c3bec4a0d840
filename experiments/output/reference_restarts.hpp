#pragma once
// The restart error (docs/analysis.md, "Restart error"): how far the scene's integrator gets
// from a reference over short horizons when both start from the same state. A chaotic run
// inherits the error of everything before an event, so comparing two whole runs after an event
// measures that history, not the method; here the reference restarts from the run's own state,
// fixed particles and manipulation progress at the start and right after each of the run's
// events, and only the difference that grows over the horizon is measured.
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>

#include "core/scene/scene.hpp"
#include "experiments/run/scene_simulation.hpp"

namespace drape {

class RestartBrancher;

/// The reference's branches off one run of a scene with `restart_error` set.
class ReferenceRestarts {
 public:
  /// Builds the reference simulation (validating it: errors name restart_error.reference).
  explicit ReferenceRestarts(const Scene& scene);
  ~ReferenceRestarts();

  /// Watches the run: branches the reference at its start and after each of its events and
  /// measures each branch when the run passes its horizon. It reads the run, never changes it.
  SimulationObserver& observer();
  /// Writes `csv` (restart_error.csv, docs/outputs.md) after the run and returns summary.json's
  /// `restart_error` entry.
  nlohmann::json write(const std::filesystem::path& csv, const Simulation& run) const;

 private:
  RestartErrorOptions m_options;
  SceneSimulation m_reference;
  std::unique_ptr<RestartBrancher> m_brancher;
};

}  // namespace drape
