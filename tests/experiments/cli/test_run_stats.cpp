// format_run_stats (experiments/cli/run_stats.hpp): the block `drapelab run` prints at the end of
// a run, one counter a line, from the run's summary.
#include "experiments/cli/run_stats.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <string>
#include <utility>

namespace {

nlohmann::json summary() {
  return nlohmann::json::parse(R"({
    "status": "ok", "integrator": "arkode-dirk", "table": "ARKODE_SDIRK_2_1_2", "adaptive": true,
    "dt": 0.001, "step_mean": 0.0025, "step_min": 0.0005, "step_max": 0.004,
    "counters": {"steps": 80, "attempts": 83, "rhs_evals": 400, "newton_iters": 250,
                 "linear_iters": 900, "jacobian_setups": 12, "error_test_failures": 2,
                 "convergence_failures": 1, "step_halvings": 0, "resets": 3},
    "events": [{}, {}, {}], "energy_drift_max_abs": 0.00125, "energy_drift_max_rel": 0.0031,
    "sim_time": 0.2, "duration": 0.2, "wall_seconds": 0.5})");
}

// The value printed after `name` on its line ("" when there is no such line).
std::string value_of(const std::string& block, const std::string& name) {
  const std::size_t at = block.find("  " + name + " ");
  if (at == std::string::npos) return "";
  const std::size_t start = block.find_first_not_of(' ', at + 2 + name.size());
  return block.substr(start, block.find('\n', start) - start);
}

TEST(RunStats, EveryCounterOnItsLine) {
  const std::string block = drape::format_run_stats(summary());
  EXPECT_EQ(block.substr(0, block.find('\n')), "status: ok");
  const std::pair<const char*, const char*> lines[] = {
      {"integrator", "arkode-dirk (ARKODE_SDIRK_2_1_2), adaptive"},
      {"steps", "80 (asked dt = 0.001 s; taken mean 0.0025 s, min 0.0005 s, max 0.004 s)"},
      {"attempted steps", "83"},
      {"rhs evaluations", "400"},
      {"newton iterations", "250"},
      {"linear iterations", "900"},
      {"jacobian setups", "12"},
      {"error test failures", "2"},
      {"convergence failures", "1"},
      {"step halvings", "0"},
      {"resets at events", "3"},
      {"events", "3"},
      {"energy drift", "0.00125 J max, 0.0031 relative"},
      {"simulated time", "0.2 s of 0.2 s"},
  };
  for (const auto& [name, value] : lines) EXPECT_EQ(value_of(block, name), value) << name;
  // 0.2 s simulated in 0.5 s of wall time: 0.4 x real time.
  EXPECT_EQ(value_of(block, "wall time"), "0.5 s (0.4 x real time)");
}

TEST(RunStats, AFailedRunSaysWhenAndWhyAndItsWarnings) {
  nlohmann::json s = summary();
  s["status"] = "diverged";
  s["time"] = 0.125;
  s["reason"] = "non-finite state";
  s["table"] = "";
  s["integrator"] = "leapfrog";
  s["adaptive"] = false;
  s["wall_seconds"] = 0.0;
  s["warnings"] = {"dt above the stability limit"};
  const std::string block = drape::format_run_stats(s);
  EXPECT_EQ(block.substr(0, block.find('\n')), "status: diverged at t = 0.125 s: non-finite state");
  EXPECT_EQ(value_of(block, "integrator"), "leapfrog");
  EXPECT_EQ(value_of(block, "wall time"), "0 s (0 x real time)");  // no division by zero
  EXPECT_NE(block.find("\nwarning: dt above the stability limit\n"), std::string::npos);
}

}  // namespace
