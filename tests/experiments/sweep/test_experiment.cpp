// Experiment definition files: cases from a shared file, and the errors of a broken definition
// (overlapping keys, values given twice, plans beyond the limit), each naming its field
// (docs/experiments.md).
#include <gtest/gtest.h>

#include "experiments/sweep/plan_size.hpp"
#include "tests/experiments/sweep/experiment_fixtures.hpp"

namespace {

using namespace drape::experiment_fixtures;

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
  // A definition in a topic folder (experiments/definitions/investigations/<topic>/) reaches the
  // shared list and its scene through "..": the same runs as the definition beside them.
  const fs::path topic = dir / "investigations" / "topic";
  fs::create_directories(topic);
  json nested = shared;
  nested["scenes"] = json::array({"../../cloth.json"});
  nested["cases"] = "../../cases/two.json";
  const auto nested_plan = drape::expand_runs(parse(nested, topic));
  ASSERT_EQ(nested_plan.size(), expected.size());
  for (std::size_t k = 0; k < nested_plan.size(); ++k) {
    EXPECT_EQ(nested_plan[k].assignments(), expected[k].assignments());
    EXPECT_EQ(fs::canonical(nested_plan[k].scene_path), fs::canonical(expected[k].scene_path));
    EXPECT_EQ(nested_plan[k].scene_digest, expected[k].scene_digest);
  }
  nested["cases"] = "../cases/two.json";  // one level short: names the field and the file
  EXPECT_EQ(error_field(nested, topic), "cases");

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
