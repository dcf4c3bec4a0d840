#pragma once
// The restart error (docs/analysis.md, "Restart error"): how far the scene's integrator gets
// from a reference over short horizons when both start from the same state. A chaotic run
// inherits the error of everything before an event, so comparing two whole runs after an event
// measures that history, not the method; here the method restarts from the reference's own
// state, fixed particles and manipulation progress at the start and right after each of the
// reference's events, and only its error over the horizon is measured.
#include <filesystem>
#include <nlohmann/json.hpp>

#include "core/scene/scene.hpp"
#include "experiments/run/scene_simulation.hpp"

namespace drape {

/// The reference run and the method's branches of one scene with `restart_error` set.
class ReferenceRestarts {
 public:
  /// Builds both simulations (validating the reference: errors name restart_error.reference).
  explicit ReferenceRestarts(const Scene& scene);

  /// Runs the reference to the end, branching the method at the start and after each event,
  /// writes `csv` (restart_error.csv, docs/outputs.md) and returns summary.json's
  /// `restart_error` entry. Never touches the scene's own run.
  nlohmann::json run(const std::filesystem::path& csv);

 private:
  RestartErrorOptions m_options;
  SceneSimulation m_reference;
  SceneSimulation m_method;
};

}  // namespace drape
