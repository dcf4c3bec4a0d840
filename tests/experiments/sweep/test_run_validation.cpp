// The check of a plan before any run (docs/experiments.md, "Bad input"): a bad value stops the
// experiment with no output folder, naming the experiment's field that gave it, or the bisection's
// probe, or the run's values together when no one of them is at fault.
#include "experiments/sweep/run_validation.hpp"

#include <gtest/gtest.h>

#include "experiments/sweep/experiment_runner.hpp"
#include "tests/experiments/sweep/experiment_fixtures.hpp"
#include "tests/support/test_support.hpp"

namespace {

using namespace drape::experiment_fixtures;

// The InputError message of running `definition` (exp.json in `dir`) into dir/out.
std::string run_error(const json& definition, const fs::path& dir) {
  drape::ExperimentOptions options;
  options.out_dir = dir / "out";
  return drape::testing::input_error_message(
      [&] { drape::run_experiment(parse(definition, dir), options); });
}

TEST(ExperimentRun, BadOverridesStopBeforeAnyRun) {
  const fs::path dir = temp_dir("bad_override");
  write_scene(dir);
  json source = two_by_three();
  source["sweep"]["integrator.name"] = json::array({"leapfrog", "runge-kutta-9"});
  const std::string exp = (dir / "exp.json").string();
  const auto error = [&](const json& definition) { return run_error(definition, dir); };
  // The value came from the experiment, so the error names its field there, not the scene's.
  EXPECT_EQ(error(source), exp + ": sweep.integrator.name: unknown integrator 'runge-kutta-9' "
                                 "(see `drapelab integrators`) (in cloth.json)");
  EXPECT_FALSE(fs::exists(dir / "out" / "results.json"));
  json unknown = two_by_three();
  unknown["sweep"]["cloth.nope"] = json::array({1});
  EXPECT_EQ(error(unknown), exp + ": sweep.cloth.nope: unknown key (in cloth.json)");
  json bad_case = two_by_three();
  bad_case["sweep"].erase("integrator.dt");
  bad_case["cases"] = json::parse(R"([{"integrator.dt": 0.001}, {"integrator.dt": -1}])");
  EXPECT_EQ(error(bad_case), exp + ": cases[1].integrator.dt: must be positive, got -1.0 (in cloth.json)");
  json bad_set = two_by_three();
  bad_set["set"] = json::parse(R"({"pins": [[0, 0, 1]]})");
  EXPECT_EQ(error(bad_set), exp + ": set.pins[0]: expected [row, col] integers, got [0, 0, 1] (in cloth.json)");
  json bad_probe = two_by_three();
  bad_probe["sweep"].erase("integrator.dt");
  bad_probe["bisect"] = json::parse(R"({"parameter": "cloth.nope", "low": 0.001, "high": 0.01})");
  EXPECT_EQ(error(bad_probe), exp + ": bisect: cloth.nope = 0.001 (bisect.low): unknown key (in cloth.json)");
  // Both ends of the bisection are checked (stiffness is bounded by 1e12 N/m).
  bad_probe["bisect"] = json::parse(R"({"parameter": "cloth.k_structural", "low": 1, "high": 1e20})");
  EXPECT_EQ(error(bad_probe), exp + ": bisect: cloth.k_structural = 1e+20 (bisect.high): must be "
                                    "at most 1000000000000.0, got 1e+20 (in cloth.json)");
  // An error the probe causes in another field is the probe's (16 x 10^6 particles).
  bad_probe["bisect"] = json::parse(R"({"parameter": "cloth.rows", "low": 2, "high": 4000000})");
  EXPECT_EQ(error(bad_probe).find(exp + ": bisect: cloth.rows = 4000000 (bisect.high): cloth.cols: "
                                       "rows x cols = 16000000 particles"), 0u)
      << error(bad_probe);
  // The probes between the ends are not integers: an integer key cannot be bisected.
  bad_probe["bisect"] = json::parse(R"({"parameter": "cloth.rows", "low": 2, "high": 30})");
  EXPECT_EQ(error(bad_probe), exp + ": bisect: cloth.rows = 7.745966692414834 (the first probe between bisect.low "
                                    "and bisect.high): expected an integer, got 7.745966692414834 (in cloth.json)");
  // A key the experiment makes inside an object the scene does not know names the experiment.
  json unknown_object = two_by_three();
  unknown_object["sweep"]["nosuch.key"] = json::array({1});
  EXPECT_EQ(error(unknown_object), exp + ": sweep.nosuch.key: unknown key (in cloth.json)");
  // A value that breaks another field (a pin off the grid a sweep made narrower) names the
  // experiment and the run's values.
  json narrow = two_by_three();
  narrow["sweep"] = json::parse(R"({"cloth.cols": [2]})");
  EXPECT_EQ(error(narrow), exp + ": " + (dir / "cloth.json").string() +
                               ": pins[1]: [0, 3] is off the 4 x 2 grid, with the run's values: "
                               "cloth.cols=2");
}

// What a run builds before its first step (the dummy, the hand recording, the step count) is
// built during the check too: bad values there stop the experiment, not each run.
TEST(ExperimentRun, BadDummyInputAndStepLimitsStopBeforeAnyRun) {
  const fs::path dir = temp_dir("bad_built");
  write_scene(dir);
  const std::string exp = (dir / "exp.json").string();
  const auto error = [&](const json& definition) { return run_error(definition, dir); };
  json dummy = two_by_three();
  dummy["set"] = json::parse(R"({"dummy": {"builtin": "cylinderx"}})");
  EXPECT_EQ(error(dummy), exp + ": set.dummy.builtin: unknown built-in dummy 'cylinderx' (known: "
                                "dress-form, cylinder, sphere) (in cloth.json)");
  json input = two_by_three();
  input["sweep"]["input"] = json::array({json::parse(R"({"events": [], "nope": 1})")});
  EXPECT_EQ(error(input), exp + ": sweep.input.nope: unknown key (in cloth.json)");
  // A recording that cannot be read names the recording.
  std::ofstream(dir / "hands.csv") << "not a recording\n";
  json recording = two_by_three();
  recording["set"] = json::parse(R"({"input": {"recording": "hands.csv"}})");
  EXPECT_EQ(error(recording).find((dir / "hands.csv").string() + ": "), 0u) << error(recording);
  json steps = two_by_three();
  steps["sweep"]["integrator.max_steps"] = json::array({10});
  // 0.05 s in steps of 1 ms is more than 10 steps: check_run_limits names the step.
  EXPECT_EQ(error(steps).find(exp + ": sweep.integrator.dt: "), 0u) << error(steps);
  EXPECT_FALSE(fs::exists(dir / "out")) << "no folder is made for an experiment that cannot run";
}

}  // namespace
