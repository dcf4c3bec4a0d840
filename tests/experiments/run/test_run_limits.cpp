// Steps that cannot advance time, or more of them than max_steps, are input errors found before
// anything is built (docs/scene.md, Limits).
#include "experiments/run/run_limits.hpp"

#include <gtest/gtest.h>

#include "experiments/run/scene_simulation.hpp"
#include "tests/support/test_support.hpp"

namespace drape {
namespace {

Scene scene_with(const std::string& integrator, double duration) {
  auto source = nlohmann::json::parse(R"({
    "cloth": {"rows": 2, "cols": 2, "spacing": 0.02, "origin": [0, 1.4, 0],
              "particle_mass": 0.001, "k_structural": 20},
    "dummy": null})");
  source["integrator"] = nlohmann::json::parse(integrator);
  source["duration"] = duration;
  return parse_scene(source, "scene.json", ".");
}

std::string error_for(const std::string& integrator, double duration) {
  const Scene scene = scene_with(integrator, duration);
  return testing::input_error_message([&] {
    check_run_limits(scene, read_integrator_options(scene.integrator, scene.file, "integrator"));
  });
}

TEST(RunLimits, AStepThatCannotAdvanceTimeIsAnInputError) {
  // At t = 1000 s, 1000 + 1e-14 == 1000: the loop would spin for ever.
  EXPECT_EQ(error_for(R"({"name": "leapfrog", "dt": 1e-14, "max_steps": 1000000000000})", 1000.0),
            "scene.json: integrator.dt: too small to advance time over duration 1000.0 s (at "
            "least duration x 2^-50)");
  EXPECT_EQ(error_for(R"({"name": "arkode-erk", "adaptive": true, "max_dt": 1e-300})", 1.0),
            "scene.json: integrator.max_dt: too small to advance time over duration 1.0 s (at "
            "least duration x 2^-50)");
}

TEST(RunLimits, StepsImpliedByDurationAreCheckedAgainstMaxSteps) {
  EXPECT_EQ(error_for(R"({"name": "leapfrog", "dt": 1e-3, "max_steps": 999})", 1.0),
            "scene.json: integrator.dt: duration / dt = 1000.0 steps, more than "
            "integrator.max_steps = 999");
  EXPECT_EQ(error_for(R"({"name": "leapfrog", "dt": 1e-3, "max_steps": 1000})", 1.0), "no error");
  EXPECT_EQ(error_for(R"({"name": "leapfrog", "dt": 1e-3})", 0.0), "no error");
}

TEST(RunLimits, SceneSimulationChecksBeforeBuilding) {
  const Scene scene = scene_with(R"({"name": "leapfrog", "dt": 1e-12})", 10.0);
  EXPECT_EQ(testing::input_error_message([&] { SceneSimulation run(scene); }),
            "scene.json: integrator.dt: duration / dt = 10000000000000.0 steps, more than "
            "integrator.max_steps = 100000000");
}

}  // namespace
}  // namespace drape
