// Running experiments: tables, resume, shards and merge, crashed runs, bisection and repeats
// (docs/experiments.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>

#include <sys/stat.h>

#include "experiments/sweep/experiment_merge.hpp"
#include "experiments/sweep/experiment_runner.hpp"
#include "tests/experiments/sweep/experiment_fixtures.hpp"

namespace {

using namespace drape::experiment_fixtures;

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

// A result.json that is no result of its run (cut, edited, from elsewhere) leaves the run
// unfinished: merge lists it with the file and what is wrong, resume reruns it.
TEST(ExperimentRun, ResultFilesThatAreNoResultAreRerunAndNamedByMerge) {
  const SmallExperiment small("bad_results");
  // References, not a structured binding: C++17 lambdas cannot capture one (clang refuses).
  const Experiment& experiment = small.experiment;
  const std::vector<drape::RunSpec>& plan = small.plan;
  const drape::ExperimentOptions& options = small.options;
  drape::run_experiment(experiment, options);
  const json whole = read_json(options.out_dir / "results.json");
  auto result_file = [&](std::size_t k) { return options.out_dir / "runs" / plan[k].id / "result.json"; };
  std::ofstream(result_file(0)) << "{}";
  std::ofstream(result_file(1)) << "[1, 2]";
  std::ofstream(result_file(2)) << "{";
  json banana = read_json(result_file(3));
  banana["status"] = "banana";
  std::ofstream(result_file(3)) << banana;
  json renamed = read_json(result_file(4));
  renamed["id"] = plan[5].id;
  std::ofstream(result_file(4)) << renamed;
  // A FIFO where run.json belongs would block the reader for ever: the run is run again.
  const fs::path spec = options.out_dir / "runs" / plan[5].id / "run.json";
  fs::remove(spec);
  ASSERT_EQ(mkfifo(spec.c_str(), 0600), 0);

  const std::vector<std::string> missing = drape::merge_results(options.out_dir, {});
  const std::vector<std::string> expected = {
      plan[0].id + ": " + result_file(0).string() + ": \"id\" is missing, not the run's id \"" +
          plan[0].id + "\"",
      plan[1].id + ": " + result_file(1).string() + ": is a JSON array, not an object",
      plan[2].id + ": " + result_file(2).string() + ": is not valid JSON",
      plan[3].id + ": " + result_file(3).string() +
          ": \"status\" is \"banana\", not one of ok, diverged, failed, error, crashed",
      plan[4].id + ": " + result_file(4).string() + ": \"id\" is \"" + plan[5].id +
          "\", not the run's id \"" + plan[4].id + "\"",
      plan[5].id + ": " + spec.string() + ": missing or unreadable"};
  EXPECT_EQ(missing, expected);
  EXPECT_EQ(read_json(options.out_dir / "results.json")["runs"].size(), 0u);

  const drape::ExperimentTally t = drape::run_experiment(experiment, options);
  EXPECT_EQ(t.skipped, 0);
  EXPECT_EQ(t.ok + t.unstable, 6);
  EXPECT_TRUE(drape::merge_results(options.out_dir, {}).empty());
  EXPECT_EQ(without_wall_time(read_json(options.out_dir / "results.json")), without_wall_time(whole));
}

// A run that segfaults or aborts ends its own child process only (docs/experiments.md,
// "Isolation"): the table has a row for every run, and resume retries the crashed one.
TEST(ExperimentRun, CrashedRunsAreRecordedAndRetriedOnResume) {
  const SmallExperiment small("crash");
  // References, not a structured binding: C++17 lambdas cannot capture one (clang refuses).
  const Experiment& experiment = small.experiment;
  const std::vector<drape::RunSpec>& plan = small.plan;
  const drape::ExperimentOptions& options = small.options;
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

// The two-by-three experiment's first case as a bisection of its step (`bisect` the spec),
// 1 s long so that the largest probe takes its step ten times (a run never shortens a step
// except to land on the end); returns the output folder.
fs::path run_bisection(const std::string& name, const char* bisect) {
  const fs::path dir = temp_dir(name);
  write_scene(dir);
  json source = two_by_three();
  source.erase("sweep");
  source["bisect"] = json::parse(bisect);
  source["set"] = json::parse(R"({"duration": 1.0})");
  drape::ExperimentOptions options;
  options.out_dir = dir / "out";
  drape::run_experiment(parse(source, dir), options);
  return options.out_dir;
}

TEST(ExperimentRun, BisectionBracketsTheLargestStableStep) {
  const fs::path out = run_bisection(
      "bisect", R"({"parameter": "integrator.dt", "low": 1e-4, "high": 0.1, "steps": 6})");
  const json row = read_json(out / "results.json")["runs"][0];
  ASSERT_EQ(row["status"], "ok") << row.dump();
  const double stable = row["stable_value"].get<double>(), unstable = row["unstable_value"].get<double>();
  EXPECT_LT(stable, unstable);
  EXPECT_NEAR(std::log(unstable / stable), std::log(0.1 / 1e-4) / 64, 1e-9);
  EXPECT_EQ(row["probes"], 8);
  // Leap-frog on a spring of k/m = 2e4 /s^2 with neighbours: stable below 2/omega_max.
  EXPECT_GT(stable, 1e-3);
  EXPECT_LT(unstable, 2.0 / std::sqrt(20.0 / 0.001));
}

TEST(ExperimentRun, BisectionWithMaxRiseCountsAProbeThatGainedEnergyAsUnstable) {
  const fs::path out = run_bisection("bisect_rise", R"({"parameter": "integrator.dt", "low": 1e-4,
                                        "high": 0.1, "steps": 6, "max_rise": 1e-8})");
  const json row = read_json(out / "results.json")["runs"][0];
  ASSERT_EQ(row["status"], "ok") << row.dump();
  const json probes =
      read_json(out / "runs" / row["id"].get<std::string>() / "bisect.json")["probes"];
  int ok_but_gaining = 0;
  for (const json& p : probes) {
    const bool ok = p["status"] == "ok";
    const double rise = p["energy_rise_max_rel"].get<double>();
    EXPECT_GE(rise, 0.0);
    EXPECT_EQ(p["stable"].get<bool>(), ok && rise <= 1e-8) << p.dump();
    ok_but_gaining += ok && rise > 1e-8;
  }
  // A bound this tight (leap-frog's own energy error at 3 ms is about 2e-7 of E(0) here) makes
  // some probe that ended ok unstable: the rise alone decides it.
  EXPECT_GE(ok_but_gaining, 1) << probes.dump();
  EXPECT_LT(row["stable_value"].get<double>(), 3e-3);
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
