#pragma once
// The progress of an experiment on stderr (docs/experiments.md, "Progress"). The experiment's
// one thread tells it when runs start, how far they are (each child's progress.json, read on
// the runner's timer) and when they finish; the reporter decides how to show it: on a terminal
// a block redrawn in place on each redraw() (bar, time left, the counts, the running runs),
// elsewhere one line per finished run, so logs stay readable. It starts no thread: the runner
// forks its runs, and forking a process with more than one thread is fragile.
#include <chrono>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "experiments/sweep/experiment_tally.hpp"

namespace drape {

/// How progress is shown: not at all, a redrawn block (terminal), or one line per finished run.
enum class ProgressStyle { Off, Terminal, Lines };

/// Collects the progress of an experiment's runs and shows it in one style.
class ProgressReporter {
 public:
  /// `total` runs in this invocation; writes to `out` (stderr in drapelab).
  ProgressReporter(int total, ProgressStyle style, std::ostream& out);
  ~ProgressReporter();
  ProgressReporter(const ProgressReporter&) = delete;
  ProgressReporter& operator=(const ProgressReporter&) = delete;

  void run_started(const std::string& id);
  /// `fraction` of the run done: its simulated time over its duration, in [0, 1].
  void run_progress(const std::string& id, double fraction);
  /// `status` ok, diverged, failed or error; `resumed` when an earlier invocation ran it.
  void run_finished(const std::string& id, const std::string& status, bool resumed);
  /// Draws the block again (Terminal style; nothing otherwise).
  void redraw();
  /// Draws the block a last time and leaves it on the screen.
  void finish();
  /// The runs counted so far (`planned` = the constructor's `total`), in any style: the
  /// experiment's final line and return value.
  const ExperimentTally& tally() const { return m_tally; }

  /// The terminal block after `elapsed` seconds: at most `width` columns a line.
  std::vector<std::string> block(int width, double elapsed) const;
  /// Seconds left after `elapsed` seconds, from the runs' own progress: elapsed x (work left) /
  /// (work done), where a run is one unit of work and a running run counts its fraction;
  /// negative when nothing is done yet.
  double seconds_left(double elapsed) const;

 private:
  double elapsed() const;

  ProgressStyle m_style;
  std::ostream& m_out;
  std::chrono::steady_clock::time_point m_start;
  bool m_finished = false;
  ExperimentTally m_tally;  ///< counted and said as the final line does
  std::map<std::string, double> m_running;  ///< id -> fraction done
  int m_drawn_lines = 0;
};

}  // namespace drape
