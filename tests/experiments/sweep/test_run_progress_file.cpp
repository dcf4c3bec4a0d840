// progress.json of a running run: the simulated fraction written every 1 %, read back by the
// parent's progress display, a bisection's probes as parts of one run.
#include "experiments/sweep/run_progress_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <vector>

#include "core/scene/scene.hpp"
#include "experiments/runner/run_scene.hpp"

namespace {

namespace fs = std::filesystem;

// Reads progress.json back after every step, as the parent would at any moment.
class ReadBack : public drape::RunProgressFile {
 public:
  using RunProgressFile::RunProgressFile;
  void on_step(const drape::Simulation& simulation, bool event) override {
    RunProgressFile::on_step(simulation, event);
    times.push_back(simulation.time());
    fractions.push_back(drape::read_run_progress(dir).value_or(-1.0));
  }
  fs::path dir;
  std::vector<double> times, fractions;
};

TEST(RunProgressFile, WritesTheSimulatedFractionEveryPercent) {
  const fs::path dir = fs::path(::testing::TempDir()) / "run_progress_file";
  fs::remove_all(dir);
  const auto source = nlohmann::json::parse(R"({
    "cloth": {"rows": 3, "cols": 3, "spacing": 0.02, "origin": [0, 1.4, 0],
              "particle_mass": 0.001, "k_structural": 20},
    "pins": [[0, 0]], "dummy": null,
    "integrator": {"name": "leapfrog", "dt": 0.0005}, "duration": 0.1})");
  ReadBack observer(dir);
  observer.dir = dir;
  drape::run_scene(drape::parse_scene(source, "test.json", "."), dir, &observer);
  ASSERT_EQ(observer.times.size(), 200u);  // 0.1 s at 0.5 ms
  for (std::size_t k = 0; k < observer.times.size(); ++k) {
    const double now = observer.times[k] / 0.1, shown = observer.fractions[k];
    // Never ahead of the run, never more than 1 % behind it.
    EXPECT_LE(shown, now + 1e-12) << k;
    EXPECT_GT(shown, now - 0.01 - 1e-12) << k;
  }
  EXPECT_DOUBLE_EQ(observer.fractions.back(), 1.0);
  std::ifstream in(drape::progress_file(dir));
  const auto doc = nlohmann::json::parse(in);
  EXPECT_DOUBLE_EQ(doc["time"].get<double>(), 0.1);
  EXPECT_DOUBLE_EQ(doc["duration"].get<double>(), 0.1);
}

TEST(RunProgressFile, ProbesArePartsOfOneRun) {
  drape::RunProgressFile progress("unused");
  EXPECT_DOUBLE_EQ(progress.run_fraction(0.5), 0.5);
  progress.set_part(1, 4);
  EXPECT_DOUBLE_EQ(progress.run_fraction(0.5), 0.375);  // (1 + 0.5) / 4
  progress.set_part(3, 4);
  EXPECT_DOUBLE_EQ(progress.run_fraction(1.0), 1.0);
  EXPECT_DOUBLE_EQ(progress.run_fraction(2.0), 1.0);  // clamped
  progress.set_part(9, 4);                            // past the last part: the last
  EXPECT_DOUBLE_EQ(progress.run_fraction(0.0), 0.75);
}

TEST(RunProgressFile, ReadsNothingFromAMissingOrForeignFile) {
  const fs::path dir = fs::path(::testing::TempDir()) / "run_progress_foreign";
  fs::remove_all(dir);
  fs::create_directories(dir);
  EXPECT_FALSE(drape::read_run_progress(dir).has_value());
  std::ofstream(drape::progress_file(dir)) << "{\"fraction\": \"half\"}";
  EXPECT_FALSE(drape::read_run_progress(dir).has_value());
  std::ofstream(drape::progress_file(dir)) << "{\"fraction\": 0.25}";
  EXPECT_DOUBLE_EQ(drape::read_run_progress(dir).value(), 0.25);
}

}  // namespace
