// Ensemble statistics (docs/experiments.md, "Ensembles"): n, mean, sample std and the Student-t
// 95% half-width on known data, and summary.csv's groups.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "experiments/sweep/ensemble_summary.hpp"

namespace drape {
namespace {

namespace fs = std::filesystem;

TEST(EnsembleSummary, StudentQuantilesMatchTables) {
  // Two-sided 95% critical values of Student's t (any statistics table).
  EXPECT_NEAR(student_t_quantile(0.975, 1), 12.7062047362, 1e-8);
  EXPECT_NEAR(student_t_quantile(0.975, 2), 4.3026527297, 1e-8);
  EXPECT_NEAR(student_t_quantile(0.975, 4), 2.7764451052, 1e-8);
  EXPECT_NEAR(student_t_quantile(0.975, 10), 2.2281388520, 1e-8);
  EXPECT_NEAR(student_t_quantile(0.975, 30), 2.0422724563, 1e-8);
  EXPECT_NEAR(student_t_quantile(0.975, 100000), 1.959963985, 1e-4);
}

TEST(EnsembleSummary, StatsOfKnownData) {
  const SampleStats s = sample_stats({1.0, 2.0, 3.0, 4.0, 5.0});
  EXPECT_EQ(s.n, 5);
  EXPECT_DOUBLE_EQ(s.mean, 3.0);
  EXPECT_NEAR(s.std, std::sqrt(2.5), 1e-15);  // sum of squares 10 over n - 1 = 4
  EXPECT_NEAR(s.ci95, 2.7764451052 * std::sqrt(2.5) / std::sqrt(5.0), 1e-8);
  const SampleStats one = sample_stats({7.0});
  EXPECT_EQ(one.n, 1);
  EXPECT_EQ(one.mean, 7.0);
  EXPECT_TRUE(std::isnan(one.std));
  EXPECT_TRUE(std::isnan(one.ci95));
}

std::vector<std::vector<std::string>> read_csv(const fs::path& file) {
  std::ifstream in(file);
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells;
    std::stringstream s(line);
    for (std::string cell; std::getline(s, cell, ',');) cells.push_back(cell);
    if (!line.empty() && line.back() == ',') cells.push_back("");
    rows.push_back(cells);
  }
  return rows;
}

TEST(EnsembleSummary, OneRowPerGroupWithEveryNumericMetric) {
  std::vector<nlohmann::json> rows;
  const double a[] = {1.0, 2.0, 3.0}, b[] = {10.0, 14.0, 18.0};
  for (int r = 0; r < 3; ++r) {
    rows.push_back({{"index", 2 * r}, {"id", "x"}, {"scene", "s.json"}, {"status", "ok"},
                    {"is_reference", false}, {"manipulation.hold_ramp", 0.0},
                    {"perturbation.seed", r + 1}, {"vibration", a[r]}, {"steps", 100}});
    rows.push_back({{"index", 2 * r + 1}, {"id", "y"}, {"scene", "s.json"}, {"status", "ok"},
                    {"is_reference", false}, {"manipulation.hold_ramp", 0.1},
                    {"perturbation.seed", r + 1}, {"vibration", b[r]}, {"steps", 100}});
  }
  const fs::path file = fs::path(::testing::TempDir()) / "ensemble_summary.csv";
  write_ensemble_summary(file, {"manipulation.hold_ramp", "perturbation.seed"}, rows);
  const auto csv = read_csv(file);
  ASSERT_EQ(csv.size(), 3u);  // header and two groups
  const auto& header = csv[0];
  auto column = [&](const std::string& name) {
    const auto it = std::find(header.begin(), header.end(), name);
    EXPECT_NE(it, header.end()) << name;
    return static_cast<std::size_t>(it - header.begin());
  };
  EXPECT_EQ(std::find(header.begin(), header.end(), "perturbation.seed"), header.end());
  EXPECT_EQ(csv[1][column("manipulation.hold_ramp")], "0.0");
  EXPECT_EQ(csv[1][column("n")], "3");
  EXPECT_DOUBLE_EQ(std::stod(csv[1][column("vibration_mean")]), 2.0);
  EXPECT_DOUBLE_EQ(std::stod(csv[1][column("vibration_std")]), 1.0);
  EXPECT_NEAR(std::stod(csv[1][column("vibration_ci95")]), 4.3026527297 / std::sqrt(3.0), 1e-8);
  EXPECT_DOUBLE_EQ(std::stod(csv[2][column("vibration_mean")]), 14.0);
  EXPECT_DOUBLE_EQ(std::stod(csv[2][column("vibration_std")]), 4.0);
  EXPECT_DOUBLE_EQ(std::stod(csv[2][column("steps_std")]), 0.0);
}

}  // namespace
}  // namespace drape
