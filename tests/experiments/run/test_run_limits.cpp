// Steps that cannot advance time, or more of them than max_steps, are input errors found before
// anything is built (docs/scene.md, Limits).
#include "experiments/run/run_limits.hpp"

#include <gtest/gtest.h>

#include "experiments/run/scene_simulation.hpp"
#include "integrators/registry/options_reader.hpp"
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

// sparse-direct's factor grows faster than the particles (2.42 GB measured at 512 x 512): a
// grid whose factor the machine cannot hold is refused before anything runs (it ended in
// std::bad_alloc after 15 GB, exit 1, with a partial energy.csv).
TEST(RunLimits, ASparseDirectFactorBeyondTheMachinesMemoryIsAnInputError) {
  const auto error_with = [](int rows, int cols, const std::string& solver, double memory) {
    Scene scene = scene_with(R"({"name": "implicit-euler", "dt": 0.01, "linear_solver": ")" +
                                 solver + R"("})",
                             0.1);
    scene.cloth.rows = rows;
    scene.cloth.cols = cols;
    const IntegratorOptions options =
        read_integrator_options(scene.integrator, scene.file, "integrator");
    return testing::input_error_message(
        [&] { check_linear_solver_memory(scene, options, "integrator", memory); });
  };
  // 4 000 000 particles: 2.42 GB x (4e6 / 512^2)^1.25 = 73.0 GB.
  EXPECT_EQ(error_with(2000, 2000, "sparse-direct", 24e9),
            "scene.json: integrator.linear_solver: sparse-direct for a 2000 x 2000 cloth needs "
            "about 73 GB (its factor grows faster than the particles: 2.42 GB measured at 512 x "
            "512), more than this machine's 24 GB; use pcg-multigrid or pcg-reduced");
  EXPECT_EQ(error_with(512, 512, "sparse-direct", 24e9), "no error");
  EXPECT_EQ(error_with(512, 512, "sparse-direct", 2e9).substr(0, 90),
            "scene.json: integrator.linear_solver: sparse-direct for a 512 x 512 cloth needs about "
            "2.42");
  EXPECT_EQ(error_with(2000, 2000, "pcg-multigrid", 24e9), "no error");
}

TEST(RunLimits, StepsImpliedByDurationAreCheckedAgainstMaxSteps) {
  EXPECT_EQ(error_for(R"({"name": "leapfrog", "dt": 1e-3, "max_steps": 999})", 1.0),
            "scene.json: integrator.dt: duration / dt = 1000.0 steps, more than "
            "integrator.max_steps = 999");
  EXPECT_EQ(error_for(R"({"name": "leapfrog", "dt": 1e-3, "max_steps": 1000})", 1.0), "no error");
  EXPECT_EQ(error_for(R"({"name": "leapfrog", "dt": 1e-3})", 0.0), "no error");
  // An adaptive run takes at least duration / max_dt steps.
  EXPECT_EQ(error_for(R"({"name": "arkode-erk", "adaptive": true, "max_dt": 1e-9})", 1.0),
            "scene.json: integrator.max_dt: duration / max_dt = 1000000000.0 steps, more than "
            "integrator.max_steps = 100000000");
  EXPECT_EQ(error_for(R"({"name": "arkode-erk", "adaptive": true, "max_dt": 1e-8})", 1.0),
            "no error");
  EXPECT_EQ(error_for(R"({"name": "arkode-erk", "adaptive": true})", 1e6), "no error");
}

// A fixed step longer than the run would be cut to the duration: not the step the scene names.
TEST(RunLimits, AFixedStepLongerThanTheRunIsAnInputError) {
  EXPECT_EQ(error_for(R"({"name": "implicit-euler", "dt": 1.0})", 0.1),
            "scene.json: integrator.dt: larger than duration (0.1 s): the run would take one "
            "step of the duration, not dt");
  EXPECT_EQ(error_for(R"({"name": "implicit-euler", "dt": 0.1})", 0.1), "no error");
  EXPECT_EQ(error_for(R"({"name": "arkode-erk", "adaptive": true, "dt": 1.0})", 0.1), "no error");
}

TEST(RunLimits, SceneSimulationChecksBeforeBuilding) {
  const Scene scene = scene_with(R"({"name": "leapfrog", "dt": 1e-12})", 10.0);
  EXPECT_EQ(testing::input_error_message([&] { SceneSimulation run(scene); }),
            "scene.json: integrator.dt: duration / dt = 10000000000000.0 steps, more than "
            "integrator.max_steps = 100000000");
}

// energy.csv and hands.csv at `energy_interval: 0` get a row every step: the steps the run may
// take (duration / dt, or max_steps for an adaptive run) bound them, and past 10^9 rows the
// interval is refused, naming it.
TEST(RunLimits, ARowEveryStepIsCheckedAgainstTheOutputBound) {
  const auto rows_error = [](const std::string& integrator, double duration, double interval) {
    Scene scene = scene_with(integrator, duration);
    scene.output.energy_interval = interval;
    const IntegratorOptions options = read_integrator_options(scene.integrator, scene.file, "integrator");
    return testing::input_error_message([&] { check_output_rows(scene, options, 0.0); });
  };
  EXPECT_EQ(rows_error(R"({"name": "leapfrog", "dt": 1e-6, "max_steps": 1000000000000})", 2000.0, 0.0),
            "scene.json: output.energy_interval: 0 writes a row of energy.csv every step: up to "
            "2000000000 steps (duration / integrator.dt), more than 1000000000 rows; give an interval");
  EXPECT_EQ(rows_error(R"({"name": "leapfrog", "dt": 1e-6, "max_steps": 1000000000000})", 2000.0, 0.01),
            "no error");
  EXPECT_EQ(rows_error(R"({"name": "leapfrog", "dt": 1e-6})", 100.0, 0.0), "no error");  // 10^8
  EXPECT_EQ(rows_error(R"({"name": "arkode-erk", "adaptive": true, "max_steps": 1000000000})", 1.0, 0.0),
            "scene.json: output.energy_interval: 0 writes a row of energy.csv every step: up to "
            "1000000000 steps (integrator.max_steps), more than 1000000000 rows; give an interval");
  EXPECT_EQ(rows_error(R"({"name": "arkode-erk", "adaptive": true, "max_steps": 999999999})", 1.0, 0.0),
            "no error");
}

HandFrame frame_at(double t, std::vector<std::string> keys = {}) {
  HandFrame f;
  f.t = t;
  f.right = HandSample{Vec3(0.0, 1.0, 0.3), false};
  f.keys = std::move(keys);
  return f;
}

// A frame at every step that ends on an event: keys (at most one change each, one more when an
// attach completes), one hold per hand after each key and at the start, and a pause and resume
// per stretch of a hand's track.
TEST(RunLimits, EventFramesAreBoundedByKeysAndTrackStretches) {
  TrackPolicy policy;
  policy.max_gap = 0.2;
  // Two stretches of the right hand (a gap of 1 s), three keys.
  const HandTrack track({frame_at(0.0, {"r"}), frame_at(0.1), frame_at(1.1, {"a", "m"}), frame_at(1.2)},
                        SensorTransform{}, TimeMap{}, policy);
  ASSERT_EQ(track.runs(Hand::Right), 2u);
  ASSERT_EQ(track.runs(Hand::Left), 0u);
  EXPECT_EQ(event_frames_bound(track), 4.0 * 3 + 2 + 2 * 2);
  EXPECT_EQ(event_frames_bound(HandTrack()), 2.0);
}

// The frame files' bound counts those event frames: a trace at one frame per run (interval =
// duration) of a 100 x 100 cloth is 2 x 10^4 rows, and 10^5 keys make it 4 x 10^9.
TEST(RunLimits, KeysCountInTheFrameFilesBound) {
  auto source = nlohmann::json::parse(R"({
    "cloth": {"rows": 100, "cols": 100, "spacing": 0.02, "origin": [0, 1.4, 0],
              "particle_mass": 0.001, "k_structural": 20},
    "dummy": null, "duration": 1.0, "integrator": {"name": "leapfrog", "dt": 1e-3},
    "output": {"trace_interval": 1.0}})");
  nlohmann::json events = nlohmann::json::array();
  for (int k = 0; k < 100000; ++k) events.push_back({{"t", k * 1e-5}, {"keys", {"r"}}});
  source["input"] = {{"events", events}};
  const Scene scene = parse_scene(source, "scene.json", ".");
  EXPECT_EQ(testing::input_error_message([&] { SceneSimulation run(scene); }),
            "scene.json: output.trace_interval: would write 4e+09 rows (particles x frames, with "
            "up to 400002 frames at the input's events), more than 1000000000");
  source["input"]["events"] = nlohmann::json::array({events[0], events[1]});
  EXPECT_EQ(testing::input_error_message([&] { SceneSimulation run(parse_scene(source, "scene.json", ".")); }),
            "no error");
}

}  // namespace
}  // namespace drape
