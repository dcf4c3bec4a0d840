#pragma once
// The runs an experiment folder already holds (runs/<id>/run.json and result.json): what resume
// skips and merge copies (docs/experiments.md). A run counts only when its run.json is the
// plan's run and its result.json a valid row of it.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace drape {

/// A run's stored result: its row, or none with why (`problem` empty when there is no file yet).
/// A file that is no result of this run (cut, edited, copied from another run) leaves the run
/// unfinished, so that resume reruns it and merge lists it.
struct StoredResult {
  std::optional<nlohmann::json> row;
  std::string problem;
};

/// What a finished folder's run.json must hold to count as run `planned` (an entry of
/// experiment.json's plan, RunSpec::to_json): its definition, not its place in the plan.
nlohmann::json run_identity(nlohmann::json planned);
/// The JSON in `file`, or nothing when it is missing, unreadable, not JSON, or a FIFO or device.
std::optional<nlohmann::json> read_json_if_present(const std::filesystem::path& file);
/// The result of the plan's run `planned` in folder `dir`: none, with why, when its run.json is
/// not the run's identity (edited, or copied from another run) or its result.json is no row of it.
StoredResult finished_run(const std::filesystem::path& dir, const nlohmann::json& planned);
/// Throws InputError naming the file when the run in `dir`, finished with result row `row`,
/// lacks a file it wrote (summary.json, those of written_run_files; a bisection's bisect.json),
/// or one is cut (JSON that does not parse, a CSV file whose last line has no newline) or is no
/// regular file. A run that could not run or crashed wrote none.
void check_run_files(const std::filesystem::path& dir, const nlohmann::json& row);

}  // namespace drape
