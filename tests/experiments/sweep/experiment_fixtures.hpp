#pragma once
// Fixtures of the experiment tests (test_run_plan.cpp, test_experiment_runner.cpp): a
// temporary folder, a small scene, a small definition and readers.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "core/io/input_error.hpp"
#include "experiments/sweep/experiment.hpp"
#include "experiments/sweep/experiment_runner.hpp"

namespace drape::experiment_fixtures {

namespace fs = std::filesystem;
using drape::Experiment;
using drape::InputError;
using nlohmann::json;

inline fs::path temp_dir(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("experiment_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// A small pinned cloth with no object: a run takes milliseconds.
inline fs::path write_scene(const fs::path& dir) {
  const fs::path file = dir / "cloth.json";
  std::ofstream(file) << R"({
    "cloth": {"rows": 4, "cols": 4, "spacing": 0.02, "origin": [0, 1.4, 0],
              "particle_mass": 0.001, "k_structural": 20},
    "pins": [[0, 0], [0, 3]], "dummy": null,
    "integrator": {"name": "leapfrog", "dt": 0.001}, "duration": 0.05,
    "output": {"energy_interval": 0.01}})";
  return file;
}

inline json two_by_three() {
  return json::parse(R"({
    "name": "small", "question": "does it run?", "scenes": ["cloth.json"],
    "sweep": {"integrator.name": ["leapfrog", "symplectic-euler"],
              "integrator.dt": [0.001, 0.002, 0.0025]},
    "metrics": ["energy_drift"]})");
}

inline Experiment parse(const json& source, const fs::path& dir) {
  return drape::parse_experiment(source, (dir / "exp.json").string(), dir);
}

// The field an InputError names for a broken experiment.
inline std::string error_field(const json& source, const fs::path& dir) {
  try {
    parse(source, dir);
  } catch (const InputError& e) {
    return e.field();
  }
  return "<no error>";
}

inline json read_json(const fs::path& file) {
  std::ifstream in(file);
  return json::parse(in);
}

// Rows without the columns that differ between two executions of the same run: the wall and
// CPU time and the date it ran (provenance, docs/outputs.md).
inline json without_wall_time(json results) {
  for (auto& row : results["runs"]) {
    row.erase("wall_seconds");
    row.erase("cpu_seconds");
    row.erase("date");
  }
  results.erase("shard");
  return results;
}

// The two-by-three experiment in a fresh folder, its plan, and options to run it into out/.
struct SmallExperiment {
  explicit SmallExperiment(const std::string& name)
      : dir(temp_dir(name)),
        experiment(parse(two_by_three(), write_scene(dir).parent_path())),
        plan(drape::expand_runs(experiment)) {
    options.out_dir = dir / "out";
    options.jobs = 2;
  }
  fs::path dir;
  Experiment experiment;
  std::vector<drape::RunSpec> plan;
  drape::ExperimentOptions options;
};

}  // namespace drape::experiment_fixtures
