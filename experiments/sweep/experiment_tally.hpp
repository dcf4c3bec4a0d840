#pragma once
// What happened to the runs of one experiment invocation, counted and said in the same words by
// the progress display and the final line (docs/experiments.md, "Parallel runs, progress,
// resume").
#include <string>

namespace drape {

/// What happened to the runs of one invocation.
struct ExperimentTally {
  int planned = 0;   ///< runs in this invocation's slice
  int skipped = 0;   ///< finished before (resumed)
  int ok = 0;
  int unstable = 0;  ///< diverged or failed: a result, not an error
  int errors = 0;    ///< could not run (bad input found late, files, exceptions)
  int crashed = 0;   ///< the run's process died (signal, abort, out of memory): a bug to report

  /// Counts a run that ended now with `status` (results table's `status` column).
  void count(const std::string& status);
  /// Runs that ended or were resumed.
  int done() const { return skipped + ok + unstable + errors + crashed; }
  /// "3 ok, 1 diverged or failed, 0 could not run, 0 crashed, 2 resumed".
  std::string summary() const;
};

}  // namespace drape
