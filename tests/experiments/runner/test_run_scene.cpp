// One scene's run (docs/outputs.md): its folder holds the files summary.json says it wrote,
// summary.json is the outcome's summary, its counts are the scene's, and state.csv holds the
// final state the summary's energy is of.
#include "experiments/runner/run_scene.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "experiments/output/run_folder.hpp"
#include "experiments/viewer/csv_table.hpp"
#include "tests/experiments/run/run_fixtures.hpp"
#include "tests/support/test_support.hpp"

namespace drape {
namespace {

namespace fs = std::filesystem;

TEST(RunScene, TheFolderHoldsWhatTheSummarySaysWithTheScenesCounts) {
  const fs::path dir = fs::path(::testing::TempDir()) / "run_scene_hanging";
  fs::remove_all(dir);
  const RunOutcome outcome = run_scene(testing::hanging_scene(0.05), dir);
  EXPECT_EQ(outcome.status, "ok");
  EXPECT_EQ(outcome.exit_code, exit_ok);
  std::ifstream in(dir / "summary.json");
  const nlohmann::json summary = nlohmann::json::parse(in);
  EXPECT_EQ(summary, outcome.summary);
  EXPECT_EQ(summary["status"], "ok");
  EXPECT_EQ(summary["steps"], 50);
  EXPECT_NEAR(summary["sim_time"].get<double>(), 0.05, 1e-12);
  EXPECT_EQ(summary["particles"], 12);
  // A 3 x 4 grid: 2 x 4 + 3 x 3 = 17 structural and 2 x 2 x 3 = 12 shear springs (k_shear
  // defaults to k_structural), no bending (k_bending 0).
  EXPECT_EQ(summary["springs"], 17 + 12);
  EXPECT_EQ(summary["object_particles"], 0);
  EXPECT_FALSE(summary.contains("reason"));
  std::vector<std::string> files;
  for (const auto& entry : fs::directory_iterator(dir))
    files.push_back(entry.path().filename().string());
  std::sort(files.begin(), files.end());
  std::vector<std::string> written = written_run_files(summary, (dir / "summary.json").string());
  written.push_back("summary.json");
  std::sort(written.begin(), written.end());
  EXPECT_EQ(files, written);
}

TEST(RunScene, StateCsvIsTheFinalStateTheSummaryHasTheEnergyOf) {
  const fs::path dir = fs::path(::testing::TempDir()) / "run_scene_state";
  fs::remove_all(dir);
  const Scene scene = testing::hanging_scene(0.02);
  const RunOutcome outcome = run_scene(scene, dir);
  const CsvTable state(dir / "state.csv", {"x", "y", "z", "vx", "vy", "vz"});
  ASSERT_EQ(state.rows(), 12);
  ClothSystem system(build_cloth(scene.cloth), nullptr, scene.forces);
  Eigen::VectorXd y(72);
  for (int i = 0; i < 12; ++i)
    for (int a = 0; a < 3; ++a) {
      y[3 * i + a] = state.at(i, a);
      y[36 + 3 * i + a] = state.at(i, 3 + a);
    }
  const EnergyBreakdown e = system.energy(y.head(36), y.tail(36));
  EXPECT_NEAR(e.total(), outcome.summary["energy_final"].get<double>(),
              1e-12 * std::abs(e.total()));
}

}  // namespace
}  // namespace drape
