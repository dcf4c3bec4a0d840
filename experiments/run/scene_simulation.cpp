#include "experiments/run/scene_simulation.hpp"

#include "core/dummy/dummy_sources.hpp"
#include "experiments/run/initial_perturbation.hpp"
#include "experiments/run/run_limits.hpp"
#include "integrators/registry/options_reader.hpp"
#include "integrators/registry/registry.hpp"

namespace drape {

IntegratorOptions checked_integrator_options(const Scene& scene,
                                             const std::string& integrator_field) {
  IntegratorOptions options = read_integrator_options(scene.integrator, scene.file, integrator_field);
  check_run_limits(scene, options, integrator_field);
  return options;
}

std::shared_ptr<const Dummy> scene_dummy(const Scene& scene) {
  if (scene.dummy.is_null()) return nullptr;
  return std::make_shared<const Dummy>(make_dummy(scene.dummy, scene.file, "dummy", scene.base_dir));
}

std::optional<HandInput> scene_hand_input(const Scene& scene) {
  if (scene.input.is_null()) return std::nullopt;
  return load_hand_input(scene.input, scene.file, "input", scene.base_dir);
}

SceneSimulation::SceneSimulation(const Scene& scene, const std::string& integrator_field)
    : m_scene(scene), m_options(checked_integrator_options(scene, integrator_field)) {
  m_system = std::make_unique<ClothSystem>(build_cloth(scene.cloth), scene_dummy(scene), scene.forces);
  for (const GridPoint& pin : scene.pins) {
    const int i = m_system->cloth().index(pin.row, pin.col);
    m_system->constraints().fix_at(i, m_system->cloth().rest_positions.segment<3>(3 * i));
  }
  m_input = scene_hand_input(scene);
  check_output_rows(scene, m_options, m_input ? event_frames_bound(m_input->track) : 0.0);
  m_manipulator = std::make_unique<Manipulator>(*m_system, m_input ? &m_input->track : nullptr,
                                                scene.manipulation);
  m_integrator = make_integrator(m_options, *m_system);
  SimulationSettings settings;
  settings.duration = scene.duration;
  settings.runaway_horizon = scene.runaway_horizon;
  settings.max_steps = m_options.max_steps;
  settings.adaptive = m_options.adaptive;
  settings.dt = m_options.dt;
  settings.perturbation = scene.perturbation;
  settings.spacing = scene.cloth.spacing;
  Eigen::VectorXd initial = m_system->initial_state(0.0);
  perturb_initial_state(scene.perturbation, scene.cloth.spacing, m_system->constraints(), initial);
  m_simulation = std::make_unique<Simulation>(*m_system, *m_manipulator, *m_integrator, settings,
                                              std::move(initial));
}

}  // namespace drape
