#pragma once
// The output folder of one run (docs/outputs.md, Run folders): which files are a run's, the
// checks `drapelab run --out` makes before anything is built, and the clearing at the start of
// a run, so that a folder never mixes two runs' files and is complete only once summary.json
// exists.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace drape {

/// The names a run writes in its folder (files, and the frames/ folder).
const std::vector<std::string>& run_file_names();
/// The run files present in `dir` (empty when it does not exist).
std::vector<std::string> run_files_in(const std::filesystem::path& dir);
/// Throws InputError naming `dir` and --out when it cannot take a run: it is an existing file,
/// its nearest existing parent is not a writable folder, or it holds another run's files and
/// `overwrite` is false or they cannot all be removed. Changes nothing.
void check_run_folder(const std::filesystem::path& dir, bool overwrite);
/// Throws InputError naming `dir`, --out and the entry when one of the entries `names` of `dir`
/// (files or whole folders) cannot be removed, so that --overwrite removes all or nothing (a
/// folder it cannot empty must be found before the other files are gone).
void check_removable(const std::filesystem::path& dir, const std::vector<std::string>& names);
/// For a single run's --out (`run`, `live`): an experiment's folder (its experiment.json) is
/// refused, even with --overwrite: the run's files beside it would make the experiment refuse
/// to resume. (An experiment checks its own folder with check_run_folder.)
void check_run_folder_not_experiment(const std::filesystem::path& dir);
/// The files beside summary.json that a finished run wrote, as its `summary` (from `file`) says
/// (docs/outputs.md): energy.csv; state.csv when it ended ok; dummy.csv with object particles;
/// hands.csv with `input`; trace.csv and event_trace/*.npy with their intervals;
/// restart_error.csv with `restart_error`. An InputError names a field of the wrong type.
std::vector<std::string> written_run_files(const nlohmann::json& summary, const std::string& file);
/// Why rows of energy.csv or hands.csv whose last time is `last_t` (nothing: no rows) fall short
/// of the end of the run its `summary` describes, or "": a run writes them at the first step
/// end after each output.energy_interval and at its end, so a file cut at a line's end ends
/// more than an interval and a step (a run that stopped writes no row of its last step) before
/// sim_time. A summary without a finite sim_time is not checked.
std::string rows_short_of_end(std::optional<double> last_t, const nlohmann::json& summary);
/// Creates `dir` and removes every run file in it (nothing else), summary.json first.
void clear_run_folder(const std::filesystem::path& dir);

}  // namespace drape
