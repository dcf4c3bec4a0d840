// Experiment plans: sweeps, cases, run ids, ensembles, references and shards
// (docs/experiments.md; a definition file's errors: test_experiment.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "tests/experiments/sweep/experiment_fixtures.hpp"

namespace {

using namespace drape::experiment_fixtures;

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
  EXPECT_EQ(plan[0].id.rfind("cloth-dt0.001-leapfrog-", 0), 0u) << plan[0].id;

  json more = two_by_three();
  more["sweep"]["integrator.dt"] = json::array({0.0005, 0.001, 0.002, 0.0025});
  const auto bigger = drape::expand_runs(parse(more, dir));
  std::set<std::string> bigger_ids;
  for (const auto& run : bigger) bigger_ids.insert(run.id);
  for (const auto& id : ids) EXPECT_TRUE(bigger_ids.count(id)) << id;
}

// An edited scene is another run: the id and run.json carry the file's digest, so resume and
// merge never take the results of the scene as it was (they did: the id held only its name).
TEST(ExperimentPlan, EditingTheSceneFileChangesTheRunIds) {
  const fs::path dir = temp_dir("edited");
  const fs::path scene = write_scene(dir);
  const auto before = drape::expand_runs(parse(two_by_three(), dir));
  std::ofstream(scene, std::ios::app) << "\n";  // the same scene, other bytes: a new digest
  const auto after = drape::expand_runs(parse(two_by_three(), dir));
  ASSERT_EQ(before.size(), after.size());
  for (std::size_t k = 0; k < before.size(); ++k) {
    EXPECT_NE(before[k].id, after[k].id);
    EXPECT_NE(before[k].to_json()["scene_digest"], after[k].to_json()["scene_digest"]);
  }
}

// The files a scene names are part of a run's identity too: a recording or mesh edited in place
// gives other ids (resume took the runs made with the old file), and only the edited file's
// digest moves. A scene naming no file has no file_digests, so its runs keep their ids.
TEST(ExperimentPlan, EditingAFileTheSceneNamesChangesItsRunIds) {
  const fs::path dir = temp_dir("named_files");
  write_scene(dir);
  std::ofstream(dir / "body.obj") << "v 0 0 0\n";
  std::ofstream(dir / "hands.jsonl") << "{}\n";
  json source = two_by_three();
  source["set"] = json::parse(
      R"({"dummy": {"mesh": "body.obj", "unit": 0.01}, "input": {"recording": "hands.jsonl"}})");
  const auto before = drape::expand_runs(parse(source, dir));
  std::ofstream(dir / "body.obj", std::ios::app) << "v 1 0 0\n";
  const auto after = drape::expand_runs(parse(source, dir));
  ASSERT_EQ(before.size(), after.size());
  for (std::size_t k = 0; k < before.size(); ++k) {
    const json& was = before[k].file_digests;
    const json& is = after[k].file_digests;
    ASSERT_TRUE(was.contains("dummy.mesh") && was.contains("input.recording")) << was;
    EXPECT_NE(was["dummy.mesh"], is["dummy.mesh"]);
    EXPECT_EQ(was["input.recording"], is["input.recording"]);
    EXPECT_NE(before[k].id, after[k].id);
    EXPECT_EQ(after[k].to_json()["file_digests"], is);
  }
  for (const drape::RunSpec& run : drape::expand_runs(parse(two_by_three(), dir)))
    EXPECT_FALSE(run.to_json().contains("file_digests")) << run.id;
}

// A long scene name is cut to 120 bytes at a character's start, so the id stays valid UTF-8 and
// survives run.json (cut inside a character, resume and merge never found the run again).
TEST(ExperimentPlan, ALongNonAsciiSceneNameIsCutAtACharacter) {
  const fs::path dir = temp_dir("utf8");
  std::string name;
  for (int k = 0; k < 58; ++k) name += "\xc3\xa9";  // e-acute, two bytes each: 116 bytes
  name += "abc";                                    // 119 bytes, then more e-acutes past 120
  for (int k = 0; k < 10; ++k) name += "\xc3\xa9";
  fs::copy_file(write_scene(dir), dir / (name + ".json"));
  json source = two_by_three();
  source["scenes"] = json::array({name + ".json"});
  for (const auto& run : drape::expand_runs(parse(source, dir))) {
    const std::string slug = run.id.substr(0, run.id.rfind('-'));
    EXPECT_EQ(slug, name.substr(0, 119));
    EXPECT_EQ(json(run.id).dump(), "\"" + run.id + "\"") << "valid UTF-8";
  }
}

// A run id reads without the plan: each value after its key, a flag as its key, and a table
// name without the "ARKODE_" every SUNDIALS table carries, so that the values that tell runs
// apart fit (the main job's ids cut the table name and lost the seed, with a bare "false").
TEST(ExperimentPlan, RunIdsNameEachValue) {
  const fs::path dir = temp_dir("readable_ids");
  write_scene(dir);
  const json source = json::parse(R"({"name": "e", "scenes": ["cloth.json"], "repeats": 1,
      "cases": [{"integrator.name": "arkode-erk", "integrator.adaptive": false,
                 "integrator.table": "ARKODE_BOGACKI_SHAMPINE_4_2_3", "integrator.dt": 0.0005},
                {"integrator.name": "arkode-erk", "integrator.adaptive": true}]})");
  const auto plan = drape::expand_runs(parse(source, dir));
  ASSERT_EQ(plan.size(), 2u);
  const auto slug = [](const std::string& id) { return id.substr(0, id.rfind('-')); };
  EXPECT_EQ(slug(plan[0].id), "cloth-no-adaptive-dt0.0005-arkode-erk-BOGACKI_SHAMPINE_4_2_3-seed1");
  EXPECT_EQ(slug(plan[1].id), "cloth-adaptive-arkode-erk-seed1");
}

// An ensemble perturbs every repeat: when one case gives its own position, the other cases
// still get the default (they got none, and their repeats were identical).
TEST(ExperimentPlan, EveryCaseOfAnEnsembleIsPerturbed) {
  const fs::path dir = temp_dir("ensemble_cases");
  write_scene(dir);
  const json source = json::parse(R"({"name": "e", "scenes": ["cloth.json"], "repeats": 2,
    "cases": [{"integrator.name": "leapfrog", "perturbation.position": 0.01},
              {"integrator.name": "symplectic-euler"}]})");
  const auto plan = drape::expand_runs(parse(source, dir));
  ASSERT_EQ(plan.size(), 4u);
  for (const auto& run : plan) {
    const json parameters = run.to_json()["parameters"];
    const double expected = parameters["integrator.name"] == "leapfrog" ? 0.01 : 1e-3;
    EXPECT_EQ(parameters.value("perturbation.position", 0.0), expected) << run.id;
  }
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

// A case that gives `integrator` whole: the reference inherited the object (its table, say,
// under the reference's own name and step), and a clash of the two was the case's error.
TEST(ExperimentPlan, AReferenceTakesNoIntegratorValueOfTheRunGivenWhole) {
  const fs::path dir = temp_dir("reference_whole_integrator");
  write_scene(dir);
  json source = json::parse(R"({
    "name": "whole", "question": "q", "scenes": ["cloth.json"],
    "cases": [{"integrator": {"name": "arkode-dirk", "dt": 0.001, "table": "ARKODE_SDIRK_2_1_2"}},
              {"integrator": {"name": "arkode-erk", "dt": 0.001, "adaptive": true, "rtol": 1e-4}}],
    "reference": {"integrator.dt": 0.0001},
    "restart_error": {"horizons": [0.02]}})");
  const auto plan = drape::expand_runs(parse(source, dir));
  ASSERT_EQ(plan.size(), 2u + 1u);  // both cases share one reference
  for (const auto& run : plan) {
    if (run.is_reference) {
      EXPECT_EQ(run.parameters, (std::vector<drape::Override>{{"integrator.dt", 0.0001}}));
      continue;
    }
    EXPECT_EQ(run.reference, plan.back().id);
    const auto restart = std::find_if(run.overrides.begin(), run.overrides.end(),
                                      [](const auto& o) { return o.first == "restart_error"; });
    ASSERT_NE(restart, run.overrides.end()) << run.id;
    // The scene's method at the reference's step: no table, no tolerance of the case.
    EXPECT_EQ(restart->second["reference"], json::parse(R"({"name": "leapfrog", "dt": 0.0001})"));
  }
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
  for (const char* bad : {"0/3", "4/3", "3", "a/b", "1/0", "1/2x", "+1/2", "01/2", " 1/2", "1/ 2"})
    EXPECT_THROW(drape::parse_shard(bad), InputError) << bad;
}

}  // namespace
