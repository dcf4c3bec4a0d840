// A scene turned into a running simulation: the cloth with its pins, the integrator it names,
// no object and no hands when the scene has none; errors in the integrator's values name the
// field they were read from.
#include "experiments/run/scene_simulation.hpp"

#include <gtest/gtest.h>

#include "tests/experiments/run/run_fixtures.hpp"
#include "tests/support/test_support.hpp"

namespace drape {
namespace {

TEST(SceneSimulation, BuildsTheScenesClothPinsAndIntegrator) {
  SceneSimulation run(testing::hanging_scene(0.05));
  EXPECT_EQ(run.system().num_particles(), 12);
  EXPECT_EQ(run.system().constraints().fixed_particles(), (std::vector<int>{0}));
  EXPECT_EQ(run.options().name, "leapfrog");
  EXPECT_EQ(run.options().dt, 0.001);
  EXPECT_FALSE(run.has_input());
  EXPECT_EQ(run.input(), nullptr);
  EXPECT_EQ(scene_dummy(run.scene()), nullptr);
  EXPECT_EQ(run.simulation().time(), 0.0);
  EXPECT_EQ(run.simulation().state(), run.system().initial_state(0.0));
}

TEST(SceneSimulation, TheObjectIsBuiltFromTheScene) {
  Scene scene = testing::hanging_scene(0.05);
  scene.dummy = nlohmann::json{{"builtin", "sphere"}, {"radius", 0.05}, {"center", {0.0, 1.0, 0.0}}};
  const auto dummy = scene_dummy(scene);
  ASSERT_NE(dummy, nullptr);
  for (int o = 0; o < dummy->size(); ++o)
    ASSERT_NEAR((dummy->position(o) - Vec3(0.0, 1.0, 0.0)).norm(), 0.05, 1e-12) << o;
  scene.dummy["builtin"] = "cube";
  const std::string error = testing::input_error_message([&] { scene_dummy(scene); });
  EXPECT_EQ(error.rfind("test.json: dummy.builtin: ", 0), 0u) << error;
}

TEST(SceneSimulation, IntegratorErrorsNameTheFieldTheyCameFrom) {
  Scene scene = testing::hanging_scene(0.05);
  scene.integrator["name"] = "runge-kutta-9";
  EXPECT_EQ(testing::input_error_message([&] { checked_integrator_options(scene); }),
            "test.json: integrator.name: unknown integrator 'runge-kutta-9' (see `drapelab integrators`)");
  const std::string reference = testing::input_error_message(
      [&] { checked_integrator_options(scene, "restart_error.reference"); });
  EXPECT_EQ(reference.rfind("test.json: restart_error.reference.name: ", 0), 0u) << reference;
  // 50 steps of 1 ms cannot fit in 10: the run limits name the step.
  scene = testing::hanging_scene(0.05);
  scene.integrator["max_steps"] = 10;
  const std::string steps = testing::input_error_message([&] { SceneSimulation run(scene); });
  EXPECT_EQ(steps.rfind("test.json: integrator.dt: ", 0), 0u) << steps;
}

}  // namespace
}  // namespace drape
