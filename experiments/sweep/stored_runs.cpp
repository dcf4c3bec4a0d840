#include "experiments/sweep/stored_runs.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <optional>

#include "core/io/input_error.hpp"
#include "core/io/json_reader.hpp"
#include "experiments/output/run_folder.hpp"
#include "experiments/sweep/experiment_folder.hpp"
#include "experiments/sweep/results_table.hpp"

namespace drape {

namespace fs = std::filesystem;

namespace {

// The result.json of run `id` in `dir`.
StoredResult read_result(const fs::path& dir, const std::string& id) {
  const fs::path file = dir / experiment_run_file::result;
  if (!fs::exists(file)) return {};
  if (const auto reason = unreadable_file_reason(file.string()))
    return {std::nullopt, file.string() + ": " + *reason};
  std::ifstream in(file);
  nlohmann::json row = nlohmann::json::parse(in, nullptr, false);
  const std::string problem = row.is_discarded() ? "is not valid JSON" : result_row_problem(row, id);
  if (!problem.empty()) return {std::nullopt, file.string() + ": " + problem};
  return {std::move(row), ""};
}

// Why the CSV file at `path` is cut, or "": every line a run writes ends in a newline, so a file
// that does not was cut (a full disk, a killed copy) inside its last line.
std::string cut_reason(const fs::path& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (in.tellg() <= 0) return "empty file (a run writes its header line first)";
  in.seekg(-1, std::ios::end);
  return in.get() == '\n' ? "" : "the last line is cut (the file does not end in a newline)";
}

// The time (first field) of the CSV file's last row, nothing when the header is its only line;
// read from its last 4 kB, where a run's row of a few hundred bytes ends. NaN for a last line
// that does not start with a number: for the file's readers to name.
std::optional<double> last_row_time(const fs::path& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  const std::streamoff size = in.tellg();
  const std::streamoff start = std::max<std::streamoff>(0, size - 4096);
  in.seekg(start);
  std::string tail(static_cast<std::size_t>(size - start), '\0');
  in.read(tail.data(), static_cast<std::streamsize>(tail.size()));
  while (!tail.empty() && (tail.back() == '\n' || tail.back() == '\r')) tail.pop_back();
  const std::size_t line = tail.rfind('\n');
  if (line == std::string::npos && start == 0) return std::nullopt;  // the header alone
  const std::string last = tail.substr(line == std::string::npos ? 0 : line + 1);
  double t = 0.0;
  const auto [end, ec] = std::from_chars(last.data(), last.data() + last.size(), t);
  if (ec != std::errc() || (end != last.data() + last.size() && *end != ','))
    return std::nan("");
  return t;
}

}  // namespace

// What a finished folder's run.json must hold to count as this run: its definition, not its
// place. `planned` is the run as RunSpec::to_json (an entry of experiment.json's plan).
nlohmann::json run_identity(nlohmann::json planned) {
  planned.erase("index");
  planned.erase("reference");
  return planned;
}

// A FIFO or a device where a JSON file belongs counts as no file (opening it would wait for a
// writer for ever); a run with one is run again, which clears its folder first.
std::optional<nlohmann::json> read_json_if_present(const fs::path& file) {
  if (unreadable_file_reason(file.string())) return std::nullopt;
  std::ifstream in(file);
  if (!in) return std::nullopt;
  nlohmann::json value = nlohmann::json::parse(in, nullptr, false);
  if (value.is_discarded()) return std::nullopt;
  return value;
}

// The result of the plan's run `planned` (an entry of experiment.json's plan) in folder `dir`,
// as read_result: a folder whose run.json is not the run's identity (edited, or copied from
// another run) holds no result of it, neither for resume nor for merge.
StoredResult finished_run(const fs::path& dir, const nlohmann::json& planned) {
  const fs::path file = dir / experiment_run_file::identity;
  const auto spec = read_json_if_present(file);
  if (spec && *spec != run_identity(planned))
    return {std::nullopt, file.string() + ": is not this run of the plan"};
  StoredResult result = read_result(dir, planned["id"].get<std::string>());
  if (result.row && !spec) return {std::nullopt, file.string() + ": missing or unreadable"};
  return result;
}

// Merge takes a run by its result.json, written last; a file of the run damaged or lost since
// (a copy cut short, a cleanup) would be listed as finished and dropped by the report silently.
void check_run_files(const fs::path& dir, const nlohmann::json& row) {
  const std::string status = row.value("status", "");
  if (status == "error" || status == "crashed") return;
  const auto require = [&](const fs::path& path, const char* why) {
    if (const auto reason = unreadable_file_reason(path.string()))
      throw InputError(path.string(), "", *reason + why);
  };
  const char* finished = " (its run finished: result.json)";
  if (row.contains("bisect_parameter")) {
    require(dir / experiment_run_file::bisection, finished);
    read_json_file((dir / experiment_run_file::bisection).string());
    return;
  }
  const std::string summary_file = (dir / "summary.json").string();
  require(summary_file, finished);
  const nlohmann::json summary = read_json_file(summary_file);
  if (!summary.is_object()) throw InputError(summary_file, "", "expected a JSON object");
  for (const std::string& name : written_run_files(summary, summary_file)) {
    const fs::path path = dir / name;
    require(path, " (the run wrote it: summary.json)");
    std::string cut = path.extension() == ".csv" ? cut_reason(path) : "";
    // A file cut at a line's end still ends in a newline: its rows stop short of the run's end.
    if (cut.empty() && name == "energy.csv")
      if (const auto t = last_row_time(path); !(t && std::isnan(*t)))
        cut = rows_short_of_end(t, summary);
    if (!cut.empty()) throw InputError(path.string(), "", cut);
  }
}

}  // namespace drape
