// energy.csv (docs/outputs.md): a row at the start and at the first step end at or after each
// multiple of output.energy_interval, with the step's own time, every step with interval 0;
// each row's total the sum of its terms, and the summary's drift the largest change of the rows.
#include "experiments/output/series_writers.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "experiments/runner/run_scene.hpp"
#include "experiments/viewer/csv_table.hpp"
#include "tests/experiments/run/run_fixtures.hpp"

namespace drape {
namespace {

namespace fs = std::filesystem;

/// The hanging cloth's energy.csv with `interval`, and the run's summary.
std::pair<CsvTable, nlohmann::json> energy_rows(double interval, const std::string& name) {
  Scene scene = testing::hanging_scene(0.02);
  scene.output.energy_interval = interval;
  const fs::path dir = fs::path(::testing::TempDir()) / ("series_writers_" + name);
  fs::remove_all(dir);
  const auto result = run_scene(scene, dir);
  return {CsvTable(dir / "energy.csv", {"t", "kinetic", "spring", "gravity", "collision", "total"}),
          result.summary};
}

std::vector<double> times(const CsvTable& table) {
  std::vector<double> t;
  for (int r = 0; r < table.rows(); ++r) t.push_back(table.at(r, 0));
  return t;
}

TEST(SeriesWriters, EnergyRowsAtTheFirstStepEndAfterEachMultiple) {
  // Multiples of 2.5 ms reached by 1 ms steps: 0, 3, 5, 8, 10, 13, 15, 18, 20 ms.
  const auto [table, summary] = energy_rows(0.0025, "interval");
  const std::vector<double> expected = {0.0, 0.003, 0.005, 0.008, 0.01, 0.013, 0.015, 0.018, 0.02};
  const std::vector<double> got = times(table);
  ASSERT_EQ(got.size(), expected.size());
  for (std::size_t k = 0; k < got.size(); ++k) EXPECT_NEAR(got[k], expected[k], 1e-12) << k;
  double drift = 0.0;
  for (int r = 0; r < table.rows(); ++r) {
    const double sum = table.at(r, 1) + table.at(r, 2) + table.at(r, 3) + table.at(r, 4);
    EXPECT_NEAR(table.at(r, 5), sum, 1e-14 * std::abs(sum)) << "row " << r;
    drift = std::max(drift, std::abs(table.at(r, 5) - table.at(0, 5)));
  }
  EXPECT_GT(drift, 0.0);
  EXPECT_DOUBLE_EQ(summary["energy_drift_max_abs"].get<double>(), drift);
  EXPECT_DOUBLE_EQ(summary["energy_drift_max_rel"].get<double>(), drift / std::abs(table.at(0, 5)));
}

TEST(SeriesWriters, IntervalZeroIsEveryStep) {
  const auto [table, summary] = energy_rows(0.0, "every_step");
  const std::vector<double> got = times(table);
  ASSERT_EQ(got.size(), 21u) << "the start and 20 steps";
  for (std::size_t k = 0; k < got.size(); ++k) EXPECT_NEAR(got[k], 0.001 * k, 1e-12) << k;
  EXPECT_EQ(summary["steps"], 20);
}

}  // namespace
}  // namespace drape
