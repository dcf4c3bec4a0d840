// `drapelab run`'s progress block: redrawn at each 1 % of the simulated time (at most 101
// times a run), ending on the run's status, and the run's steps are the same with it as without.
#include "experiments/cli/run_progress_display.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>

#include "core/scene/scene.hpp"
#include "experiments/runner/run_scene.hpp"

namespace {

namespace fs = std::filesystem;

int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(RunProgressDisplay, RedrawsEveryPercentAndEndsOnTheStatus) {
  const auto source = nlohmann::json::parse(R"({
    "cloth": {"rows": 3, "cols": 3, "spacing": 0.02, "origin": [0, 1.4, 0],
              "particle_mass": 0.001, "k_structural": 20},
    "pins": [[0, 0]], "dummy": null,
    "integrator": {"name": "leapfrog", "dt": 0.0002}, "duration": 0.1})");
  const fs::path dir = fs::path(::testing::TempDir()) / "run_progress_display";
  std::ostringstream out;
  drape::RunProgressDisplay progress("test.json", out);
  const drape::RunOutcome shown =
      drape::run_scene(drape::parse_scene(source, "test.json", "."), dir / "shown", &progress);
  progress.finish(shown.status);
  const std::string text = out.str();
  // 500 steps of 0.2 %: a redraw (clear to the end of the screen) at the start, then one when
  // the fraction has grown by 1 % (every 5 steps, or 6 where 5 x 0.2 % rounds below 1 %), and
  // the last at finish(): between 500 / 6 + 2 and 102.
  const int redraws = count(text, "\r\x1b[J");
  EXPECT_GE(redraws, 85);
  EXPECT_LE(redraws, 102);
  EXPECT_NE(text.find("test.json"), std::string::npos);
  EXPECT_NE(text.rfind("1/1 "), std::string::npos) << text.substr(text.size() - 200);
  EXPECT_NE(text.rfind("  1 ok, 0 diverged or failed"), std::string::npos) << text.substr(text.size() - 200);
  const drape::RunOutcome plain =
      drape::run_scene(drape::parse_scene(source, "test.json", "."), dir / "plain");
  EXPECT_EQ(shown.summary.at("energy_final"), plain.summary.at("energy_final"));
  EXPECT_EQ(shown.summary.at("rhs_evals"), plain.summary.at("rhs_evals"));
}

}  // namespace
