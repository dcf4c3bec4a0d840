// Experiment files, plans, run ids, resume, shards and merge (docs/experiments.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>

#include "core/scene/input_error.hpp"
#include "experiments/sweep/experiment.hpp"
#include "experiments/sweep/experiment_runner.hpp"

namespace {

namespace fs = std::filesystem;
using drape::Experiment;
using drape::InputError;
using nlohmann::json;

fs::path temp_dir(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("experiment_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// A small pinned cloth with no object: a run takes milliseconds.
fs::path write_scene(const fs::path& dir) {
  const fs::path file = dir / "cloth.json";
  std::ofstream(file) << R"({
    "cloth": {"rows": 4, "cols": 4, "spacing": 0.02, "origin": [0, 1.4, 0],
              "particle_mass": 0.001, "k_structural": 20},
    "pins": [[0, 0], [0, 3]], "dummy": null,
    "integrator": {"name": "leapfrog", "dt": 0.001}, "duration": 0.05,
    "output": {"energy_interval": 0.01}})";
  return file;
}

json two_by_three() {
  return json::parse(R"({
    "name": "small", "question": "does it run?", "scenes": ["cloth.json"],
    "sweep": {"integrator.name": ["leapfrog", "symplectic-euler"],
              "integrator.dt": [0.001, 0.002, 0.0025]},
    "metrics": ["energy_drift"]})");
}

Experiment parse(const json& source, const fs::path& dir) {
  return drape::parse_experiment(source, (dir / "exp.json").string(), dir);
}

// The field an InputError names for a broken experiment.
std::string error_field(const json& source, const fs::path& dir) {
  try {
    parse(source, dir);
  } catch (const InputError& e) {
    return e.field();
  }
  return "<no error>";
}

json read_json(const fs::path& file) {
  std::ifstream in(file);
  return json::parse(in);
}

// Rows without the columns that differ between two executions of the same run: the wall time
// and the date it ran (provenance, docs/outputs.md).
json without_wall_time(json results) {
  for (auto& row : results["runs"]) {
    row.erase("wall_seconds");
    row.erase("date");
  }
  results.erase("shard");
  return results;
}

TEST(ExperimentPlan, SweepIsTheCartesianProductAndCasesMultiplyIt) {
  const fs::path dir = temp_dir("plan");
  write_scene(dir);
  auto plan = drape::expand_runs(parse(two_by_three(), dir));
  ASSERT_EQ(plan.size(), 6u);
  std::set<std::pair<std::string, double>> combos;
  for (std::size_t k = 0; k < plan.size(); ++k) {
    EXPECT_EQ(plan[k].index, static_cast<int>(k));
    ASSERT_EQ(plan[k].parameters.size(), 2u);
    combos.insert({plan[k].parameters[1].second.get<std::string>(),
                   plan[k].parameters[0].second.get<double>()});
  }
  EXPECT_EQ(combos.size(), 6u);

  json with_cases = two_by_three();
  with_cases["sweep"].erase("integrator.name");
  with_cases["cases"] = json::parse(R"([{"integrator.name": "leapfrog"},
      {"integrator.name": "symplectic-euler", "cloth.damping_spring": 0.01}])");
  plan = drape::expand_runs(parse(with_cases, dir));
  ASSERT_EQ(plan.size(), 6u);
  EXPECT_EQ(plan[5].parameters.size(), 3u);
  EXPECT_EQ(plan[5].assignments().back(), "integrator.dt=0.0025");
}

TEST(ExperimentPlan, RunIdsAreStableUniqueAndIndependentOfPlanPosition) {
  const fs::path dir = temp_dir("ids");
  write_scene(dir);
  const auto plan = drape::expand_runs(parse(two_by_three(), dir));
  std::set<std::string> ids;
  for (const auto& run : plan) ids.insert(run.id);
  EXPECT_EQ(ids.size(), plan.size());
  // The id of one run is a fixed function of its definition: pinned here so that a change to
  // the hashing, which would orphan every finished folder, is deliberate.
  EXPECT_EQ(plan[0].id, drape::run_id(plan[0]));
  EXPECT_EQ(plan[0].id.rfind("cloth-0.001-leapfrog-", 0), 0u) << plan[0].id;

  json more = two_by_three();
  more["sweep"]["integrator.dt"] = json::array({0.0005, 0.001, 0.002, 0.0025});
  const auto bigger = drape::expand_runs(parse(more, dir));
  std::set<std::string> bigger_ids;
  for (const auto& run : bigger) bigger_ids.insert(run.id);
  for (const auto& id : ids) EXPECT_TRUE(bigger_ids.count(id)) << id;
}

TEST(ExperimentPlan, ReferenceRunsShareNonIntegratorValuesAndAreAppendedOnce) {
  const fs::path dir = temp_dir("reference");
  write_scene(dir);
  json source = two_by_three();
  source["sweep"]["cloth.damping_spring"] = json::array({0.0, 0.01});
  source["reference"] = json::parse(R"({"integrator.name": "leapfrog", "integrator.dt": 0.0001})");
  const auto plan = drape::expand_runs(parse(source, dir));
  ASSERT_EQ(plan.size(), 12u + 2u);  // one reference per damping value
  for (int k = 0; k < 12; ++k) {
    ASSERT_FALSE(plan[k].reference.empty());
    const auto& ref = *std::find_if(plan.begin(), plan.end(),
                                    [&](const auto& r) { return r.id == plan[k].reference; });
    EXPECT_TRUE(ref.is_reference);
    EXPECT_EQ(ref.parameters.front(), plan[k].parameters.front());  // the damping value
  }
}

TEST(ExperimentPlan, RestartErrorGivesEveryRunItsReferencesIntegrator) {
  const fs::path dir = temp_dir("restart_error");
  write_scene(dir);
  json source = two_by_three();
  source["set"] = json::parse(R"({"integrator.max_steps": 100000})");
  source["reference"] = json::parse(R"({"integrator.dt": 0.0001})");
  source["restart_error"] = json::parse(R"({"horizons": [0.02, 0.04]})");
  const auto plan = drape::expand_runs(parse(source, dir));
  ASSERT_EQ(plan.size(), 6u + 1u);
  for (const auto& run : plan) {
    const auto restart = std::find_if(run.overrides.begin(), run.overrides.end(),
                                      [](const auto& o) { return o.first == "restart_error"; });
    if (run.is_reference) {
      EXPECT_EQ(restart, run.overrides.end());
      continue;
    }
    ASSERT_NE(restart, run.overrides.end()) << run.id;
    // The reference run's integrator as its scene reads it: the scene's method, the experiment's
    // set and the reference's values (not the run's own integrator values).
    EXPECT_EQ(restart->second["reference"],
              json::parse(R"({"name": "leapfrog", "dt": 0.0001, "max_steps": 100000})"));
    EXPECT_EQ(restart->second["horizons"], json::parse("[0.02, 0.04]"));
  }
  json no_reference = two_by_three();
  no_reference["restart_error"] = json::parse(R"({"horizons": [0.02]})");
  EXPECT_EQ(error_field(no_reference, dir), "restart_error");
  source["restart_error"] = json::parse(R"({"horizons": [0.02], "every": 1})");
  EXPECT_EQ(error_field(source, dir), "restart_error.every");
}

TEST(ExperimentPlan, ShardsPartitionThePlanExactlyOnce) {
  for (int n = 1; n <= 7; ++n) {
    std::vector<int> seen(20, 0);
    for (int k = 1; k <= n; ++k)
      for (int i = 0; i < 20; ++i) seen[i] += drape::Shard{k, n}.contains(i);
    for (int i = 0; i < 20; ++i) EXPECT_EQ(seen[i], 1) << "run " << i << " of " << n << " shards";
  }
  EXPECT_EQ(drape::parse_shard("3/8").index, 3);
  EXPECT_EQ(drape::parse_shard("3/8").count, 8);
  for (const char* bad : {"0/3", "4/3", "3", "a/b", "1/0", "1/2x"})
    EXPECT_THROW(drape::parse_shard(bad), InputError) << bad;
}

// `cases` may name a file beside the definition holding {"cases": [...]}: the same plan as the
// list inline; its errors name that file, a missing one the definition's field.
TEST(ExperimentFile, CasesFromASharedFileAreTheInlineCases) {
  const fs::path dir = temp_dir("cases_file");
  write_scene(dir);
  const json list = json::parse(R"([{"integrator.name": "leapfrog"},
      {"integrator.name": "symplectic-euler", "cloth.damping_spring": 0.01}])");
  json inline_cases = two_by_three();
  inline_cases["sweep"].erase("integrator.name");
  inline_cases["cases"] = list;
  fs::create_directories(dir / "cases");
  std::ofstream(dir / "cases" / "two.json") << json{{"cases", list}}.dump();
  json shared = inline_cases;
  shared["cases"] = "cases/two.json";
  const auto expected = drape::expand_runs(parse(inline_cases, dir));
  const auto plan = drape::expand_runs(parse(shared, dir));
  ASSERT_EQ(plan.size(), 6u);
  for (std::size_t k = 0; k < plan.size(); ++k) {
    EXPECT_EQ(plan[k].assignments(), expected[k].assignments());
    EXPECT_EQ(plan[k].id, expected[k].id);
  }

  for (const char* bad : {"cases/missing.json", "cases", "", "/etc/hostname"}) {
    shared["cases"] = bad;
    EXPECT_EQ(error_field(shared, dir), "cases") << bad;
  }
  shared["cases"] = 5;
  EXPECT_EQ(error_field(shared, dir), "cases");
  auto error_in = [&](const json& content) -> std::pair<std::string, std::string> {
    std::ofstream(dir / "cases" / "bad.json") << content.dump();
    json definition = inline_cases;
    definition["cases"] = "cases/bad.json";
    try {
      parse(definition, dir);
    } catch (const InputError& e) {
      return {fs::path(e.file()).filename().string(), e.field()};
    }
    return {"", "<no error>"};
  };
  using Where = std::pair<std::string, std::string>;
  EXPECT_EQ(error_in(json{{"cases", json::array({json{{"a..b", 1}}})}}), Where("bad.json", "cases[0].a..b"));
  EXPECT_EQ(error_in(json{{"cases", list}, {"colour", 1}}), Where("bad.json", "colour"));
  EXPECT_EQ(error_in(json{{"cases", json::array()}}), Where("bad.json", "cases"));
  EXPECT_EQ(error_in(json::array()), Where("bad.json", ""));
  EXPECT_EQ(error_in(json{{"cases", "two.json"}}), Where("bad.json", "cases"));
  EXPECT_EQ(error_in(json{{"cases", json::array({1})}}), Where("bad.json", "cases[0]"));
  // a clash with the definition's sweep (integrator.dt) is reported in the cases file
  EXPECT_EQ(error_in(json{{"cases", json::array({json{{"integrator.dt", 0.01}}})}}),
            Where("bad.json", "cases[0].integrator.dt"));
}

TEST(ExperimentFile, ErrorsNameTheField) {
  const fs::path dir = temp_dir("errors");
  write_scene(dir);
  auto with = [](const char* key, json value) {
    json j = two_by_three();
    j[key] = std::move(value);
    return j;
  };
  EXPECT_EQ(error_field(with("colour", 1), dir), "colour");
  EXPECT_EQ(error_field(with("scenes", json::array({"missing.json"})), dir), "scenes[0]");
  EXPECT_EQ(error_field(with("scenes", json::array()), dir), "scenes");
  EXPECT_EQ(error_field(with("metrics", json::array({"energy_drift", "beauty"})), dir), "metrics[1]");
  EXPECT_EQ(error_field(with("duration", -1), dir), "duration");
  json empty_sweep = two_by_three();
  empty_sweep["sweep"]["integrator.dt"] = json::array();
  EXPECT_EQ(error_field(empty_sweep, dir), "sweep.integrator.dt");
  json clash = two_by_three();
  clash["cases"] = json::parse(R"([{"integrator.dt": 0.001}])");
  EXPECT_EQ(error_field(clash, dir), "cases[0].integrator.dt");
  json no_name = two_by_three();
  no_name.erase("name");
  EXPECT_EQ(error_field(no_name, dir), "name");
  json bad_bisect = two_by_three();
  bad_bisect["bisect"] = json::parse(R"({"low": 0.01, "high": 0.001})");
  EXPECT_EQ(error_field(bad_bisect, dir), "bisect.high");
}

TEST(ExperimentRun, BadOverridesStopBeforeAnyRun) {
  const fs::path dir = temp_dir("bad_override");
  write_scene(dir);
  json source = two_by_three();
  source["sweep"]["integrator.name"] = json::array({"leapfrog", "runge-kutta-9"});
  drape::ExperimentOptions options;
  options.out_dir = dir / "out";
  EXPECT_THROW(drape::run_experiment(parse(source, dir), options), InputError);
  EXPECT_FALSE(fs::exists(dir / "out" / "results.json"));
}

TEST(ExperimentRun, WritesTablesResumesAndMergesShardsToTheSameResults) {
  const fs::path dir = temp_dir("run");
  write_scene(dir);
  const Experiment experiment = parse(two_by_three(), dir);
  drape::ExperimentOptions options;
  options.out_dir = dir / "whole";
  options.jobs = 2;
  drape::ExperimentTally t = drape::run_experiment(experiment, options);
  EXPECT_EQ(t.planned, 6);
  EXPECT_EQ(t.ok + t.unstable, 6);
  EXPECT_EQ(t.errors, 0);
  const json whole = read_json(options.out_dir / "results.json");
  ASSERT_EQ(whole["runs"].size(), 6u);
  EXPECT_EQ(whole["runs"][0]["status"], "ok");
  EXPECT_EQ(whole["runs"][0]["steps"], 50);
  EXPECT_TRUE(whole["runs"][0].contains("integrator.dt"));
  EXPECT_TRUE(whole["runs"][0].contains("energy_drift_max_rel"));
  EXPECT_TRUE(fs::exists(options.out_dir / "results.csv"));
  EXPECT_TRUE(fs::exists(options.out_dir / "runs" / whole["runs"][0]["id"].get<std::string>() /
                         "energy.csv"));

  // Resume: nothing reruns; an interrupted run (no result.json) and a foreign folder rerun.
  const fs::path first = options.out_dir / "runs" / whole["runs"][1]["id"].get<std::string>();
  const fs::path second = options.out_dir / "runs" / whole["runs"][2]["id"].get<std::string>();
  fs::remove(first / "result.json");
  std::ofstream(second / "run.json") << R"({"id": "something else"})";
  t = drape::run_experiment(experiment, options);
  EXPECT_EQ(t.skipped, 4);
  EXPECT_EQ(t.ok + t.unstable, 2);
  EXPECT_EQ(without_wall_time(read_json(options.out_dir / "results.json")), without_wall_time(whole));

  // Three shards into three folders (three machines), then one merge.
  std::vector<fs::path> shard_dirs;
  for (int k = 1; k <= 3; ++k) {
    drape::ExperimentOptions shard = options;
    shard.out_dir = dir / ("shard" + std::to_string(k));
    shard.shard = drape::Shard{k, 3};
    t = drape::run_experiment(experiment, shard);
    EXPECT_EQ(t.planned, 2);
    EXPECT_TRUE(fs::exists(shard.out_dir / "shards" / (std::to_string(k) + "-of-3.json")));
    shard_dirs.push_back(shard.out_dir);
  }
  const fs::path merged = dir / "merged";
  EXPECT_EQ(drape::merge_results(merged, {shard_dirs[0]}).size(), 4u);  // two shards missing
  EXPECT_TRUE(drape::merge_results(merged, shard_dirs).empty());
  EXPECT_EQ(without_wall_time(read_json(merged / "results.json")), without_wall_time(whole));
}

// A run that segfaults or aborts ends its own child process only (docs/experiments.md,
// "Isolation"): the table has a row for every run, and resume retries the crashed one.
TEST(ExperimentRun, CrashedRunsAreRecordedAndRetriedOnResume) {
  const fs::path dir = temp_dir("crash");
  write_scene(dir);
  const Experiment experiment = parse(two_by_three(), dir);
  const std::vector<drape::RunSpec> plan = drape::expand_runs(experiment);
  drape::ExperimentOptions options;
  options.out_dir = dir / "out";
  options.jobs = 2;
  auto run_with_crash = [&](const std::string& request) {
    ::setenv("DRAPELAB_TEST_CRASH", request.c_str(), 1);
    const drape::ExperimentTally t = drape::run_experiment(experiment, options);
    ::unsetenv("DRAPELAB_TEST_CRASH");
    return t;
  };
  auto row = [&](std::size_t k) { return read_json(options.out_dir / "results.json")["runs"][k]; };

  drape::ExperimentTally t = run_with_crash("segv:" + plan[1].id);
  EXPECT_EQ(t.crashed, 1);
  EXPECT_EQ(t.ok + t.unstable, 5);
  ASSERT_EQ(read_json(options.out_dir / "results.json")["runs"].size(), 6u);
  EXPECT_EQ(row(1)["status"], "crashed");
  EXPECT_EQ(row(1)["reason"], "signal 11 (SIGSEGV)");
  EXPECT_EQ(row(1)["id"], plan[1].id);
  EXPECT_EQ(row(0)["status"], "ok");
  EXPECT_EQ(read_json(options.out_dir / "runs" / plan[1].id / "result.json")["status"], "crashed");

  t = run_with_crash("abort:" + plan[1].id);  // resume retries the crashed run, only it
  EXPECT_EQ(t.skipped, 5);
  EXPECT_EQ(t.crashed, 1);
  EXPECT_EQ(row(1)["reason"], "signal 6 (SIGABRT)");

  t = drape::run_experiment(experiment, options);  // the cause gone, it finishes
  EXPECT_EQ(t.skipped, 5);
  EXPECT_EQ(t.crashed, 0);
  EXPECT_EQ(row(1)["status"], "ok");
  EXPECT_EQ(row(1)["steps"], row(0)["steps"]);
}

TEST(ExperimentRun, BisectionBracketsTheLargestStableStep) {
  const fs::path dir = temp_dir("bisect");
  write_scene(dir);
  json source = two_by_three();
  source.erase("sweep");
  source["bisect"] = json::parse(R"({"parameter": "integrator.dt", "low": 1e-4, "high": 0.1,
                                     "steps": 6})");
  // Long enough that the largest probe takes its step ten times (a run never shortens a step
  // except to land on the end).
  source["set"] = json::parse(R"({"duration": 1.0})");
  drape::ExperimentOptions options;
  options.out_dir = dir / "out";
  drape::run_experiment(parse(source, dir), options);
  const json row = read_json(options.out_dir / "results.json")["runs"][0];
  ASSERT_EQ(row["status"], "ok") << row.dump();
  const double stable = row["stable_value"].get<double>(), unstable = row["unstable_value"].get<double>();
  EXPECT_LT(stable, unstable);
  EXPECT_NEAR(std::log(unstable / stable), std::log(0.1 / 1e-4) / 64, 1e-9);
  EXPECT_EQ(row["probes"], 8);
  // Leap-frog on a spring of k/m = 2e4 /s^2 with neighbours: stable below 2/omega_max.
  EXPECT_GT(stable, 1e-3);
  EXPECT_LT(unstable, 2.0 / std::sqrt(20.0 / 0.001));
}

TEST(ExperimentRun, RepeatsAreSeededReproducibleAndSummarised) {
  const fs::path dir = temp_dir("repeats");
  write_scene(dir);
  const json source = json::parse(R"({
    "name": "ensemble", "scenes": ["cloth.json"], "repeats": 3,
    "sweep": {"integrator.dt": [0.001, 0.002]}})");
  const Experiment experiment = parse(source, dir);
  const auto plan = drape::expand_runs(experiment);
  ASSERT_EQ(plan.size(), 6u);
  EXPECT_EQ(plan[0].parameters.back(), drape::Override("perturbation.seed", 1));
  EXPECT_EQ(plan[2].parameters.back(), drape::Override("perturbation.seed", 3));
  EXPECT_NE(std::find(plan[0].overrides.begin(), plan[0].overrides.end(),
                      drape::Override("perturbation.position", 1e-3)),
            plan[0].overrides.end())
      << "repeats perturb by 1e-3 spacing unless the experiment says otherwise";
  drape::ExperimentOptions options;
  options.out_dir = dir / "a";
  options.jobs = 2;
  EXPECT_EQ(drape::run_experiment(experiment, options).ok, 6);
  const json a = read_json(options.out_dir / "results.json");
  EXPECT_NE(a["runs"][0]["energy_final"], a["runs"][1]["energy_final"]) << "seeds differ";
  options.out_dir = dir / "b";
  drape::run_experiment(experiment, options);
  const json b = read_json(options.out_dir / "results.json");
  for (std::size_t k = 0; k < 6; ++k)
    EXPECT_EQ(a["runs"][k]["energy_final"], b["runs"][k]["energy_final"]) << "same seed, same run";
  std::ifstream summary(dir / "a" / "summary.csv");
  std::string header, line;
  ASSERT_TRUE(std::getline(summary, header));
  EXPECT_EQ(header.rfind("scene,is_reference,integrator.dt,n,", 0), 0u) << header;
  EXPECT_NE(header.find("energy_final_ci95"), std::string::npos);
  int groups = 0;
  while (std::getline(summary, line)) groups += line.find(",3,") != std::string::npos;
  EXPECT_EQ(groups, 2);
  EXPECT_EQ(error_field(json::parse(R"({"name": "e", "scenes": ["cloth.json"], "repeats": 0})"), dir),
            "repeats");
}

}  // namespace
