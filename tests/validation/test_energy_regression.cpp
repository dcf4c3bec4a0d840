// Energy drift of each explicit integrator on fixed scenes against stored baselines with explicit
// tolerances (tests/regression/energy_drift_baselines.json; regenerate as its `regenerate` says).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/scene/scene.hpp"
#include "experiments/runner/run_scene.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const fs::path regression_dir = fs::path(DRAPE_SOURCE_DIR) / "tests" / "regression";

json baselines() {
  std::ifstream in(regression_dir / "energy_drift_baselines.json");
  return json::parse(in);
}

// The checked values of a run, named as in the experiment's results table.
double measured(const json& summary, const std::string& metric) {
  if (metric == "energy_drift_final_rel") {
    const double e0 = summary["energy_initial"], e1 = summary["energy_final"];
    return std::abs(e1 - e0) / std::abs(e0);
  }
  return summary.at(metric).get<double>();
}

// rel_tol: |x - value| <= rel_tol |value| (floats); pct_tol: the same in percent (counters).
double allowed(const json& expect) {
  const double value = std::abs(expect["value"].get<double>());
  if (expect.contains("rel_tol")) return expect["rel_tol"].get<double>() * value;
  return expect.at("pct_tol").get<double>() / 100.0 * value;
}

class EnergyRegression : public ::testing::TestWithParam<int> {};

TEST_P(EnergyRegression, DriftMatchesBaseline) {
  const json entry = baselines()["runs"][GetParam()];
  std::vector<std::string> overrides;
  for (const auto& item : entry["overrides"].items()) overrides.push_back(item.key() + "=" + item.value().dump());
  const drape::Scene scene =
      drape::load_scene((regression_dir / entry["scene"].get<std::string>()).string(), overrides);
  const fs::path out = fs::path(::testing::TempDir()) / ("energy_regression_" + std::to_string(GetParam()));
  const drape::RunOutcome outcome = drape::run_scene(scene, out);
  ASSERT_EQ(outcome.status, "ok") << outcome.reason;
  for (const auto& item : entry["expect"].items()) {
    const double expected = item.value()["value"].get<double>();
    EXPECT_NEAR(measured(outcome.summary, item.key()), expected, allowed(item.value()))
        << entry["scene"] << " " << entry["overrides"].dump() << ": " << item.key()
        << " (regenerate: see energy_drift_baselines.json)";
  }
}

INSTANTIATE_TEST_SUITE_P(Baselines, EnergyRegression,
                         ::testing::Range(0, static_cast<int>(baselines()["runs"].size())));

}  // namespace
