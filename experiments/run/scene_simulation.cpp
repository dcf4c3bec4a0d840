#include "experiments/run/scene_simulation.hpp"

#include "core/dummy/dummy_sources.hpp"
#include "experiments/run/initial_perturbation.hpp"
#include "experiments/run/run_limits.hpp"
#include "integrators/interface/registry.hpp"

namespace drape {

SceneSimulation::SceneSimulation(const Scene& scene, const std::string& integrator_field)
    : m_scene(scene),
      m_options(read_integrator_options(scene.integrator, scene.file, integrator_field)) {
  check_run_limits(scene, m_options, integrator_field);
  std::shared_ptr<const Dummy> dummy;
  if (!scene.dummy.is_null())
    dummy = std::make_shared<const Dummy>(make_dummy(scene.dummy, scene.file, "dummy", scene.base_dir));
  m_system = std::make_unique<ClothSystem>(build_cloth(scene.cloth), dummy, scene.forces);
  for (const GridPoint& pin : scene.pins) {
    const int i = m_system->cloth().index(pin.row, pin.col);
    m_system->constraints().fix_at(i, m_system->cloth().rest_positions.segment<3>(3 * i));
  }
  if (!scene.input.is_null())
    m_input = load_hand_input(scene.input, scene.file, "input", scene.base_dir);
  m_manipulator = std::make_unique<Manipulator>(*m_system, m_input ? &m_input->track : nullptr,
                                                scene.manipulation);
  m_integrator = make_integrator(m_options, *m_system);
  SimulationSettings settings;
  settings.duration = scene.duration;
  settings.max_steps = m_options.max_steps;
  settings.adaptive = m_options.adaptive;
  settings.dt = m_options.dt;
  settings.perturbation = scene.perturbation;
  settings.spacing = scene.cloth.spacing;
  Eigen::VectorXd initial = m_system->initial_state(0.0);
  perturb_initial_positions(scene.perturbation, scene.cloth.spacing, m_system->constraints(),
                            initial);
  m_simulation = std::make_unique<Simulation>(*m_system, *m_manipulator, *m_integrator, settings,
                                              std::move(initial));
}

}  // namespace drape
