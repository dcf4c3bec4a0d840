#pragma once
// A scene turned into a running simulation: the model, the dummy, the hand input, the
// manipulator and the integrator it names, built once and owned together.
#include <memory>
#include <optional>
#include <string>

#include "core/input/input_config.hpp"
#include "core/scene/scene.hpp"
#include "experiments/run/simulation.hpp"
#include "integrators/interface/integrator_options.hpp"

namespace drape {

/// The parts of a run built from its scene that can fail on its input, each throwing InputError
/// naming the scene file and the field: the integrator's options read from `integrator_field`
/// and checked against the run limits (run_limits.hpp), the object (null without one) and the
/// hand input (none without one). SceneSimulation builds a run from them; an experiment checks
/// every run with them before any runs (sweep/run_validation.cpp).
IntegratorOptions checked_integrator_options(const Scene& scene,
                                             const std::string& integrator_field = "integrator");
std::shared_ptr<const Dummy> scene_dummy(const Scene& scene);
std::optional<HandInput> scene_hand_input(const Scene& scene);

/// Everything one scene runs with. Throws InputError (naming the scene file and the field) for
/// invalid input found while building; errors in the integrator name `integrator_field` (the
/// restart error's reference is read from another field).
class SceneSimulation {
 public:
  explicit SceneSimulation(const Scene& scene, const std::string& integrator_field = "integrator");

  Simulation& simulation() { return *m_simulation; }
  const Simulation& simulation() const { return *m_simulation; }
  const Scene& scene() const { return m_scene; }
  const IntegratorOptions& options() const { return m_options; }
  const ClothSystem& system() const { return *m_system; }
  bool has_input() const { return m_input.has_value(); }
  /// The hand input the manipulator reads; the live mode adds keys to its track between steps.
  HandInput* input() { return m_input ? &*m_input : nullptr; }

 private:
  Scene m_scene;
  IntegratorOptions m_options;
  std::unique_ptr<ClothSystem> m_system;
  std::optional<HandInput> m_input;
  std::unique_ptr<Manipulator> m_manipulator;
  std::unique_ptr<Integrator> m_integrator;
  std::unique_ptr<Simulation> m_simulation;
};

}  // namespace drape
