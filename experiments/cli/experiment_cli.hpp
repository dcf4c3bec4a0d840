#pragma once
// The `experiment`, `merge` and `report` subcommands of drapelab (docs/experiments.md).
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace drape {

/// Runs an experiment file (or one shard of it) into out_dir; `--list` prints the plan only.
/// Returns 0 when every run ran (diverged runs are results), 1 when some could not run.
/// Throws InputError for an out_dir that cannot take it (check_experiment_folder).
int experiment_command(const std::string& file, const std::string& out_dir, int jobs, int threads,
                       const std::string& shard, bool list_only, bool progress, bool overwrite);
/// Joins the runs of shards: copies sources' runs into out_dir and writes its results table.
/// Returns 0 when the plan is complete, 1 when runs are missing (listed on stderr).
int merge_command(const std::string& out_dir, const std::vector<std::string>& sources);
/// Writes the plots and report.html of an experiment folder with analysis/report.py.
int report_command(const std::string& dir, const std::vector<std::string>& extra_args);

/// The options of the three subcommands; dispatch() runs whichever was parsed.
class ExperimentCommands {
 public:
  /// Adds `experiment`, `merge` and `report` to the app.
  explicit ExperimentCommands(CLI::App& app);
  // The app keeps pointers to the members: an instance must stay where it was built.
  ExperimentCommands(const ExperimentCommands&) = delete;
  ExperimentCommands& operator=(const ExperimentCommands&) = delete;
  /// Runs the parsed subcommand if it is one of these; returns -1 when it is not.
  /// Throws InputError for bad input (the caller exits with status 2).
  int dispatch() const;

 private:
  CLI::App* m_experiment = nullptr;
  CLI::App* m_merge = nullptr;
  CLI::App* m_report = nullptr;
  std::string m_file, m_out, m_shard;
  int m_jobs = 0;
  int m_threads = 0;  // 0: all cores / jobs
  bool m_list = false;
  bool m_no_progress = false;
  bool m_overwrite = false;
  std::vector<std::string> m_sources;
};

}  // namespace drape
