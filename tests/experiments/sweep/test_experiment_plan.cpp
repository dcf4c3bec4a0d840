// Experiment definitions and plans: sweeps, cases, run ids, references, shards and the
// errors of a broken definition (docs/experiments.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "experiments/sweep/plan_size.hpp"
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
  EXPECT_EQ(plan[0].id.rfind("cloth-0.001-leapfrog-", 0), 0u) << plan[0].id;

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

// A long scene name is cut to 72 bytes at a character's start, so the id stays valid UTF-8 and
// survives run.json (cut inside a character, resume and merge never found the run again).
TEST(ExperimentPlan, ALongNonAsciiSceneNameIsCutAtACharacter) {
  const fs::path dir = temp_dir("utf8");
  std::string name;
  for (int k = 0; k < 30; ++k) name += "\xc3\xa9";  // e-acute, two bytes each: 60 bytes
  name += "abc";                                    // 63 bytes, then more e-acutes past 72
  for (int k = 0; k < 10; ++k) name += "\xc3\xa9";
  fs::copy_file(write_scene(dir), dir / (name + ".json"));
  json source = two_by_three();
  source["scenes"] = json::array({name + ".json"});
  for (const auto& run : drape::expand_runs(parse(source, dir))) {
    const std::string slug = run.id.substr(0, run.id.rfind('-'));
    EXPECT_EQ(slug.substr(0, 63), name.substr(0, 63));
    EXPECT_LE(slug.size(), 72u);
    EXPECT_EQ(json(run.id).dump(), "\"" + run.id + "\"") << "valid UTF-8";
  }
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
  for (const char* bound : {"max_drift", "max_rise"}) {
    bad_bisect["bisect"] = json::parse(R"({"low": 0.001, "high": 0.01})");
    bad_bisect["bisect"][bound] = -1.0;
    EXPECT_EQ(error_field(bad_bisect, dir), std::string("bisect.") + bound);
    bad_bisect["bisect"][bound] = "x";
    EXPECT_EQ(error_field(bad_bisect, dir), std::string("bisect.") + bound);
  }
  for (const char* parameter : {"", "integrator..dt", ".dt"}) {
    bad_bisect["bisect"] = json::parse(R"({"low": 0.001, "high": 0.01})");
    bad_bisect["bisect"]["parameter"] = parameter;
    EXPECT_EQ(error_field(bad_bisect, dir), "bisect.parameter") << parameter;
  }
  json other_grid = two_by_three();
  other_grid["reference"] = json::parse(R"({"integrator.dt": 0.0001, "cloth.rows": 5})");
  EXPECT_EQ(error_field(other_grid, dir), "reference.cloth.rows");
  other_grid["reference"] = json::parse(R"({"cloth": {"rows": 5}})");
  EXPECT_EQ(error_field(other_grid, dir), "reference.cloth");
  // A reference is a method: another duration or gravity would make its error meaningless.
  other_grid["reference"] = json::parse(R"({"integrator.dt": 0.0001, "duration": 0.01})");
  EXPECT_EQ(error_field(other_grid, dir), "reference.duration");
  other_grid["reference"] = json::parse(R"({"integrator": {"name": "leapfrog", "dt": 1e-4},
                                            "output.vtk_interval": 0})");
  EXPECT_EQ(error_field(other_grid, dir), "<no error>") << "outputs never change the method";
  other_grid["restart_error"] = json::parse(R"({"horizons": []})");
  EXPECT_EQ(error_field(other_grid, dir), "restart_error.horizons");
}

// A scene path given twice, or inside another given elsewhere, would be decided by the order in
// which the overrides are applied: refused wherever the two come from.
TEST(ExperimentFile, OverlappingKeysAreRefused) {
  const fs::path dir = temp_dir("overlap");
  write_scene(dir);
  json whole = two_by_three();
  whole["set"] = json::parse(R"({"integrator": {"name": "leapfrog", "dt": 0.001}})");
  EXPECT_EQ(error_field(whole, dir), "set.integrator");
  json inside_set = two_by_three();
  inside_set["sweep"].erase("integrator.dt");
  inside_set["set"] = json::parse(R"({"cloth": {"rows": 4}, "cloth.cols": 4})");
  EXPECT_EQ(error_field(inside_set, dir), "set.cloth");
  json inside_sweep = two_by_three();
  inside_sweep["sweep"]["integrator"] = json::array({json::parse(R"({"dt": 0.001})")});
  EXPECT_EQ(error_field(inside_sweep, dir), "sweep.integrator");
  json inside_case = two_by_three();
  inside_case["sweep"].erase("integrator.dt");
  inside_case["cases"] = json::parse(R"([{"cloth.rows": 4, "cloth": {"cols": 4}}])");
  EXPECT_EQ(error_field(inside_case, dir), "cases[0].cloth");  // keys in JSON order
  json case_and_set = inside_case;
  case_and_set["cases"] = json::parse(R"([{"output.energy_interval": 0.01}])");
  case_and_set["set"] = json::parse(R"({"output": {"energy_interval": 0.02}})");
  EXPECT_EQ(error_field(case_and_set, dir), "cases[0].output.energy_interval");
  json apart = two_by_three();
  apart["set"] = json::parse(R"({"integrator.rtol": 1e-4, "cloth.rows": 4})");
  EXPECT_EQ(error_field(apart, dir), "<no error>") << "integrator.rtol and integrator.dt are apart";
  json deep = two_by_three();
  std::string path = "b";
  for (int k = 0; k < 64; ++k) path = "a." + path;
  deep["set"] = json{{path, 1}};
  EXPECT_EQ(error_field(deep, dir), "set." + path) << "the nesting limit holds for a key path";
  // A bisection's probe, applied last, may not replace a value; it may be merged into an object.
  json bisecting = two_by_three();
  bisecting["sweep"].erase("integrator.dt");
  bisecting["bisect"] = json::parse(R"({"parameter": "integrator.dt", "low": 0.001, "high": 0.01})");
  bisecting["set"] = json::parse(R"({"integrator.dt": 0.002})");
  EXPECT_EQ(error_field(bisecting, dir), "bisect.parameter");
  bisecting.erase("set");
  bisecting["sweep"].erase("integrator.name");
  bisecting["cases"] = json::parse(R"([{"integrator": {"name": "leapfrog", "dt": 0.002}}])");
  EXPECT_EQ(error_field(bisecting, dir), "<no error>");
  // With repeats, a whole perturbation object would replace the seeds or the default position.
  json ensemble = two_by_three();
  ensemble["repeats"] = 2;
  ensemble["set"] = json::parse(R"({"perturbation": {"position": 0.01}})");
  EXPECT_EQ(error_field(ensemble, dir), "set.perturbation");
  ensemble.erase("set");
  ensemble["sweep"]["perturbation"] = json::array({json::parse(R"({"seed": 3})")});
  EXPECT_EQ(error_field(ensemble, dir), "sweep.perturbation");
  ensemble["sweep"].erase("perturbation");
  ensemble["sweep"]["perturbation.position"] = json::array({0.01});
  EXPECT_EQ(error_field(ensemble, dir), "<no error>");
}

TEST(ExperimentFile, AValueGivenTwiceIsRefusedSinceItsRunsWouldShareOneId) {
  const fs::path dir = temp_dir("twice");
  write_scene(dir);
  json scenes = two_by_three();
  scenes["scenes"] = json::array({"cloth.json", "./cloth.json"});  // one file, two spellings
  EXPECT_EQ(error_field(scenes, dir), "scenes[1]");
  json values = two_by_three();
  values["sweep"]["integrator.dt"] = json::array({0.001, 0.002, 0.001});
  EXPECT_EQ(error_field(values, dir), "sweep.integrator.dt[2]");
  values["sweep"]["integrator.dt"] = json::array({1, 1.0});  // equal numbers
  EXPECT_EQ(error_field(values, dir), "sweep.integrator.dt[1]");
  json cases = two_by_three();
  cases["sweep"].erase("integrator.dt");
  cases["cases"] = json::parse(
      R"([{"integrator.dt": 0.001}, {"integrator.dt": 0.002}, {"integrator.dt": 0.001}])");
  EXPECT_EQ(error_field(cases, dir), "cases[2]");
  try {
    parse(cases, dir);
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("equals cases[0]"), std::string::npos) << e.what();
  }
  cases["cases"][2]["integrator.dt"] = 0.003;
  EXPECT_EQ(error_field(cases, dir), "<no error>");
}

TEST(ExperimentFile, APlanBeyondTheLimitIsRefusedFromItsCounts) {
  const fs::path dir = temp_dir("plan_size");
  write_scene(dir);
  // 9 keys x 10 values: 10^9 runs, refused before any is expanded (this returns at once).
  json huge = two_by_three();
  huge["sweep"] = json::object();
  for (int k = 0; k < 9; ++k)
    huge["sweep"]["key" + std::to_string(k) + ".x"] = json::array({0, 1, 2, 3, 4, 5, 6, 7, 8, 9});
  try {
    parse(huge, dir);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "sweep");
    EXPECT_NE(std::string(e.what()).find("1000000000 runs, more than the limit 100000"),
              std::string::npos) << e.what();
  }
  json repeats = two_by_three();
  repeats.erase("sweep");
  repeats["repeats"] = 100001;
  EXPECT_EQ(error_field(repeats, dir), "repeats");
  repeats["repeats"] = 100000;  // the limit itself is a plan
  EXPECT_DOUBLE_EQ(drape::plan_size_bound(parse(repeats, dir)), 100000.0);
  // A reference run per run can double the plan: 6 x 2 x 10000 is over the limit.
  json with_reference = two_by_three();
  with_reference["repeats"] = 10000;
  EXPECT_DOUBLE_EQ(drape::plan_size_bound(parse(with_reference, dir)), 60000.0);
  with_reference["reference"] = json::parse(R"({"integrator.dt": 0.0001})");
  EXPECT_EQ(error_field(with_reference, dir), "repeats");
}

}  // namespace
