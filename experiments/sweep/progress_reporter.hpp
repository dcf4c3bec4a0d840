#pragma once
// The progress of an experiment on stderr (docs/experiments.md, "Progress"). Runners call
// run_started / run_progress / run_finished from any thread (threads today; a child process's
// runner can forward the same three calls); the reporter decides how to show them: on a
// terminal a block redrawn every 0.5 s from its own thread (bar, counts, time left, the running
// runs), elsewhere one line per finished run, so logs stay readable.
#include <chrono>
#include <condition_variable>
#include <map>
#include <mutex>
#include <ostream>
#include <string>
#include <thread>
#include <vector>

#include "experiments/run/simulation.hpp"

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
  /// Stops redrawing and leaves the last block on the screen.
  void finish();

  /// The terminal block now: at most `width` columns a line (used by the redraw thread; public
  /// so that tests can read it without a terminal).
  std::vector<std::string> block(int width) const;
  /// Seconds left, from the runs' own progress: elapsed x (work left) / (work done), where a
  /// run is one unit of work; negative when nothing is done yet.
  double seconds_left() const;

 private:
  void redraw_loop();
  void draw_locked();
  std::vector<std::string> block_locked(int width) const;
  double seconds_left_locked() const;

  int m_total;
  ProgressStyle m_style;
  std::ostream& m_out;
  std::chrono::steady_clock::time_point m_start;
  mutable std::mutex m_mutex;
  std::condition_variable m_wake;
  bool m_stop = false;
  int m_ok = 0, m_unstable = 0, m_errors = 0, m_resumed = 0;
  std::map<std::string, double> m_running;  ///< id -> fraction done
  int m_drawn_lines = 0;
  std::thread m_redraw;
};

/// Forwards a simulation's progress (time / duration) to a reporter, at most every 1 %.
class RunProgressObserver : public SimulationObserver {
 public:
  RunProgressObserver(ProgressReporter& reporter, std::string id)
      : m_reporter(reporter), m_id(std::move(id)) {}
  void on_start(const Simulation& simulation) override { report(simulation); }
  void on_step(const Simulation& simulation, bool /*event*/) override { report(simulation); }

 private:
  void report(const Simulation& simulation);
  ProgressReporter& m_reporter;
  std::string m_id;
  double m_reported = -1.0;
};

}  // namespace drape
