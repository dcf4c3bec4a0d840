#pragma once
// Runs the plan of an experiment, each run in its own child process, resumes finished runs,
// writes the results table (docs/experiments.md); experiment_merge.hpp merges shards.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "experiments/sweep/experiment.hpp"
#include "experiments/sweep/experiment_tally.hpp"

namespace drape {

/// How to run an experiment.
struct ExperimentOptions {
  std::filesystem::path out_dir;
  int jobs = 0;                ///< runs at once (child processes); 0 = hardware concurrency
  int threads = 0;             ///< each run's threads; 0 = max(1, hardware concurrency / jobs)
  std::optional<Shard> shard;  ///< run only this slice of the plan
  bool progress = false;       ///< show progress on stderr ...
  bool terminal = false;       ///< ... redrawn in place (a terminal) or one line per finished run
  bool overwrite = false;      ///< clear out_dir's run and experiment files once the plan is valid
};

/// Runs the experiment's plan (or one shard of it) into options.out_dir and writes the table:
/// results.{csv,json} for a whole plan, shards/K-of-N.{csv,json} for a shard.
/// Throws InputError when a run's scene and overrides are invalid (checked before any run).
ExperimentTally run_experiment(const Experiment& experiment, const ExperimentOptions& options);

}  // namespace drape
