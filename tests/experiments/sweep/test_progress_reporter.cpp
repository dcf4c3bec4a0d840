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
  EXPECT_LT(progress.seconds_left(10.0), 0.0);  // nothing done: unknown
  progress.run_started("a");
  progress.run_started("b");
  progress.run_progress("a", 0.5);
  progress.run_progress("b", 0.5);
  // One run's work done of four in 10 s: three runs' work, 30 s, is left.
  EXPECT_DOUBLE_EQ(progress.seconds_left(10.0), 30.0);
  progress.run_finished("a", "ok", false);
  progress.run_finished("b", "ok", true);  // resumed: neither work done nor left
  progress.run_started("c");
  progress.run_progress("c", 0.25);
  // 1.25 of 3 units done in 10 s: 1.75 units, 14 s, left.
  EXPECT_DOUBLE_EQ(progress.seconds_left(10.0), 14.0);
  progress.run_progress("gone", 0.9);  // a run not (or no longer) running changes nothing
  EXPECT_DOUBLE_EQ(progress.seconds_left(10.0), 14.0);
  progress.finish();
  EXPECT_EQ(out.str(), "");  // Off draws nothing
}

TEST(ProgressReporter, BlockFitsEightyColumnsAndNamesTheRunningRuns) {
  std::ostringstream out;
  drape::ProgressReporter progress(3, drape::ProgressStyle::Off, out);
  const std::string long_id = "integrator.name=arkode-dirk__integrator.table=ARKODE_SDIRK_5_3_4"
                              "__integrator.dt=0.001__cloth.damping_spring=0.01-58e3f3fb";
  progress.run_started(long_id);
  progress.run_progress(long_id, 0.42);
  progress.run_started("short");
  const auto lines = progress.block(79, 5.0);
  ASSERT_EQ(lines.size(), 4u);
  for (const auto& line : lines) EXPECT_LE(line.size(), 79u) << line;
  // 0.42 of 3 runs in 5 s: 2.58 / 0.42 x 5 s = 30.7 s left.
  EXPECT_EQ(lines[0], "[--------------------] 0/3  0:05 elapsed, ~0:31 left");
  EXPECT_EQ(lines[1], "  0 ok, 0 diverged or failed, 0 could not run, 0 crashed, 0 resumed");
  // A long id keeps its start and its end (the values and hash that tell runs apart).
  EXPECT_EQ(lines[2].rfind("  integrator.name=arkode-dirk", 0), 0u) << lines[2];
  EXPECT_EQ(lines[2].size(), 79u);
  EXPECT_EQ(lines[2].substr(36, 3), "...") << lines[2];  // 34 characters either side
  EXPECT_EQ(lines[2].substr(79 - 15), "-58e3f3fb   42%") << lines[2];
  EXPECT_NE(lines[3].find("short"), std::string::npos);
  EXPECT_NE(lines[3].find("0%"), std::string::npos);
}

// The block counts in the final line's words, each status in its own class: a crashed run was
// counted as "unstable" beside the diverged ones, and the words differed from the final tally.
TEST(ProgressReporter, BlockCountsEachStatusAsTheFinalLineDoes) {
  std::ostringstream out;
  drape::ProgressReporter progress(6, drape::ProgressStyle::Off, out);
  const char* statuses[] = {"ok", "diverged", "failed", "error", "crashed"};
  for (const char* status : statuses) progress.run_finished(status, status, false);
  progress.run_finished("earlier", "ok", true);
  const auto lines = progress.block(79, 5.0);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0], "[####################] 6/6  0:05 elapsed, ~0:00 left");
  EXPECT_EQ(lines[1], "  1 ok, 2 diverged or failed, 1 could not run, 1 crashed, 1 resumed");
  // The same count is the experiment's tally (run_experiment returns it).
  const drape::ExperimentTally& t = progress.tally();
  EXPECT_EQ(t.planned, 6);
  EXPECT_EQ(t.ok, 1);
  EXPECT_EQ(t.unstable, 2);
  EXPECT_EQ(t.errors, 1);
  EXPECT_EQ(t.crashed, 1);
  EXPECT_EQ(t.skipped, 1);
}

TEST(ProgressReporter, TerminalRedrawsInPlaceOnRequest) {
  std::ostringstream out;
  drape::ProgressReporter progress(2, drape::ProgressStyle::Terminal, out);
  EXPECT_EQ(out.str(), "");  // no thread: nothing happens until the runner asks
  progress.run_started("x");
  progress.run_progress("x", 0.5);
  progress.redraw();
  const std::string first = out.str();
  EXPECT_EQ(first.rfind("\r\x1b[J[", 0), 0u) << first;
  EXPECT_NE(first.find("\n  x "), std::string::npos) << first;
  EXPECT_NE(first.find("50%"), std::string::npos) << first;
  progress.run_progress("x", 0.75);
  progress.redraw();
  // Up two lines (the block has three), clear, draw again.
  const std::string second = out.str().substr(first.size());
  EXPECT_EQ(second.rfind("\x1b[2A\r\x1b[J[", 0), 0u) << second;
  EXPECT_NE(second.find("75%"), std::string::npos) << second;
  progress.run_finished("x", "ok", false);
  progress.finish();
  EXPECT_EQ(out.str().back(), '\n');  // the last block stays, the shell prompt below it
  const std::size_t before = out.str().size();
  progress.redraw();  // finished: nothing more
  EXPECT_EQ(out.str().size(), before);
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
  // Each child's progress.json is gone with its run; the run files stay.
  int runs = 0;
  for (const auto& run : fs::directory_iterator(dir / "out" / "runs")) {
    ++runs;
    EXPECT_FALSE(fs::exists(run.path() / "progress.json")) << run.path();
    EXPECT_TRUE(fs::exists(run.path() / "result.json")) << run.path();
  }
  EXPECT_EQ(runs, 3);
  const std::string csv = drape::testing::read_text(dir / "out" / "results.csv");
  const std::string header = csv.substr(0, csv.find('\n'));
  for (const char* column : {"version", "git_commit", "build_type", "sundials_version", "date",
                             "machine.hostname", "machine.cpu", "machine.cores"})
    EXPECT_NE(header.find(std::string(",") + column), std::string::npos) << column;
}

}  // namespace
