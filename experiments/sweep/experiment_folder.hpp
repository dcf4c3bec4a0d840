#pragma once
// The output folder of an experiment (docs/experiments.md, What it writes): the checks
// `drapelab experiment --out` makes before anything is run, and the clearing `--overwrite` asks
// for, so that a folder never mixes a run's or another experiment's files with this one's.
#include <filesystem>
#include <string>
#include <vector>

namespace drape {

/// The names an experiment writes at the top of its folder (files and folders), experiment.json
/// first: clearing removes the mark of an experiment folder before the rest.
const std::vector<std::string>& experiment_file_names();
/// What an experiment adds to each run's folder (runs/<id>/) beside the run's own files
/// (run_file_names): the run's identity in the plan, its result row, its progress while it runs,
/// and a bisection's bracket and probe runs.
namespace experiment_run_file {
inline constexpr const char* identity = "run.json";
inline constexpr const char* result = "result.json";
inline constexpr const char* progress = "progress.json";
inline constexpr const char* bisection = "bisect.json";
inline constexpr const char* probes = "probes";
}  // namespace experiment_run_file
/// The names above, as a list.
const std::vector<std::string>& experiment_run_file_names();
/// Throws InputError naming `dir` and --out when it cannot take the experiment `name`: it is a
/// file, cannot be created (check_run_folder), or holds a run's files or another experiment's
/// (experiment.json with another name) and `overwrite` is false. The same experiment's folder
/// is accepted: rerunning resumes it. Changes nothing.
void check_experiment_folder(const std::filesystem::path& dir, const std::string& name,
                             bool overwrite);
/// Removes what a run and an experiment write at the top of `dir` (nothing else), experiment.json
/// first: the start of `--overwrite`.
void clear_experiment_folder(const std::filesystem::path& dir);
/// Removes the results table of an earlier invocation (results.json, results.csv, summary.csv)
/// before this one runs, so that one stopped before it writes its own cannot leave the last
/// one's beside a changed plan, which the report would show as the experiment's. Throws
/// std::filesystem::filesystem_error when one cannot be removed.
void remove_results_table(const std::filesystem::path& dir);

}  // namespace drape
