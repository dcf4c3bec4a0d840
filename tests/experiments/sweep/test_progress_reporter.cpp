// The experiment progress display: time left from the runs' own progress, the terminal block
// within 80 columns, one line per finished run elsewhere (and the provenance columns).
#include "experiments/sweep/progress_reporter.hpp"

#include <gtest/gtest.h>

#include <regex>
#include <sstream>

#include "tests/support/drapelab_process.hpp"

namespace {

TEST(ProgressReporter, TimeLeftComesFromTheRunsOwnProgress) {
  std::ostringstream out;
  drape::ProgressReporter progress(4, drape::ProgressStyle::Off, out);
  EXPECT_LT(progress.seconds_left(), 0.0);  // nothing done: unknown
  progress.run_started("a");
  progress.run_started("b");
  progress.run_progress("a", 0.5);
  progress.run_progress("b", 0.5);
  // One run's work done of four: three times the elapsed time is left.
  const double left = progress.seconds_left();
  EXPECT_GE(left, 0.0);
  progress.run_finished("a", "ok", false);
  progress.run_finished("b", "ok", true);  // resumed: neither work done nor left
  progress.run_started("c");
  progress.run_progress("c", 0.25);
  // 1.25 of 3 units done.
  EXPECT_GE(progress.seconds_left(), 0.0);
  progress.finish();
  EXPECT_EQ(out.str(), "");  // Off draws nothing
}

TEST(ProgressReporter, BlockFitsEightyColumnsAndNamesTheRunningRuns) {
  std::ostringstream out;
  drape::ProgressReporter progress(3, drape::ProgressStyle::Off, out);
  const std::string long_id = "integrator.name=arkode-dirk__integrator.table=ARKODE_SDIRK_5_3_4"
                              "__integrator.dt=0.001__cloth.damping_spring=0.01";
  progress.run_started(long_id);
  progress.run_progress(long_id, 0.42);
  progress.run_started("short");
  const auto lines = progress.block(79);
  ASSERT_EQ(lines.size(), 3u);
  for (const auto& line : lines) EXPECT_LE(line.size(), 79u) << line;
  EXPECT_EQ(lines[0].rfind("[--------------------] 0/3", 0), 0u) << lines[0];
  EXPECT_NE(lines[1].find("integrator.name=arkode-dirk"), std::string::npos);
  EXPECT_NE(lines[1].find("42%"), std::string::npos) << lines[1];
  EXPECT_NE(lines[2].find("short"), std::string::npos);
  EXPECT_NE(lines[2].find("0%"), std::string::npos);
}

TEST(ProgressReporter, LinesStylePrintsOneLinePerFinishedRun) {
  std::ostringstream out;
  drape::ProgressReporter progress(2, drape::ProgressStyle::Lines, out);
  progress.run_started("x");
  progress.run_progress("x", 0.7);
  EXPECT_EQ(out.str(), "");
  progress.run_finished("x", "diverged", false);
  progress.run_finished("y", "ok", true);
  progress.finish();
  const std::string text = out.str();
  EXPECT_TRUE(std::regex_search(text, std::regex(R"(^drapelab: \[1/2\] x diverged, 0:\d\d elapsed)")))
      << text;
  EXPECT_NE(text.find("\ndrapelab: [2/2] y ok (resumed)"), std::string::npos) << text;
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 2);
  EXPECT_EQ(text.find('\x1b'), std::string::npos);  // no terminal codes in a log
}

TEST(ProgressReporter, ExperimentOffATerminalLogsEachRunAndTabulatesProvenance) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(::testing::TempDir()) / "progress_experiment";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "cloth.json") << R"({"cloth": {"rows": 3, "cols": 3, "spacing": 0.02,
    "origin": [0, 1.4, 0], "particle_mass": 0.001, "k_structural": 20}, "pins": [[0, 0]],
    "dummy": null, "integrator": {"name": "leapfrog", "dt": 0.001}, "duration": 0.02})";
  std::ofstream(dir / "exp.json") << R"({"name": "small", "question": "progress?",
    "scenes": ["cloth.json"], "sweep": {"integrator.dt": [0.001, 0.002, 0.0025]},
    "metrics": ["energy_drift"]})";
  const auto r = drape::testing::run_drapelab("experiment " + (dir / "exp.json").string() +
                                              " --out " + (dir / "out").string() + " -j 2");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* done : {"[1/3] ", "[2/3] ", "[3/3] "})
    EXPECT_NE(r.err.find(std::string("drapelab: ") + done), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find('\x1b'), std::string::npos);
  const std::string csv = drape::testing::read_text(dir / "out" / "results.csv");
  const std::string header = csv.substr(0, csv.find('\n'));
  for (const char* column : {"version", "git_commit", "build_type", "sundials_version", "date",
                             "machine.hostname", "machine.cpu", "machine.cores"})
    EXPECT_NE(header.find(std::string(",") + column), std::string::npos) << column;
}

}  // namespace
