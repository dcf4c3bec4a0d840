#include "experiments/output/run_folder.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <utility>

#include "core/io/input_error.hpp"

namespace drape {

namespace fs = std::filesystem;

namespace {

InputError folder_error(const fs::path& dir, const std::string& message) {
  return InputError(dir.string(), "--out", message);
}

bool writable_folder(const fs::path& dir) {
  return ::access(dir.c_str(), W_OK | X_OK) == 0;
}

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& name : names) out += (out.empty() ? "" : ", ") + name;
  return out;
}

// The first entry below `path` that removing it would fail on: an entry of a folder that is not
// writable, or a folder that cannot be listed. Nothing for a file or a link (its own folder
// decides) and for a tree that can go.
std::optional<fs::path> removal_blocker(const fs::path& path) {
  std::error_code ec;
  if (!fs::is_directory(fs::symlink_status(path, ec))) return std::nullopt;
  fs::recursive_directory_iterator entry(path, ec);
  if (ec) return path;
  for (; entry != fs::recursive_directory_iterator(); entry.increment(ec)) {
    if (ec) return path;
    if (!writable_folder(entry->path().parent_path())) return entry->path();
  }
  if (ec) return path;
  return std::nullopt;
}

// The number at `pointer` ("/scene/output/trace_interval") of a run's summary, 0 when absent.
double summary_number(const nlohmann::json& summary, const std::string& file,
                      const std::string& pointer) {
  const nlohmann::json::json_pointer at(pointer);
  if (!summary.contains(at)) return 0.0;
  const nlohmann::json& value = summary[at];
  if (!value.is_number() || !std::isfinite(value.get<double>())) {
    std::string field = pointer.substr(1);
    std::replace(field.begin(), field.end(), '/', '.');
    throw InputError(file, field, "expected a finite number, got " + shorten(value.dump()));
  }
  return value.get<double>();
}

}  // namespace

void check_removable(const fs::path& dir, const std::vector<std::string>& names) {
  for (const auto& name : names)
    if (const auto blocker = removal_blocker(dir / name))
      throw folder_error(dir, "cannot replace its files: " + blocker->string() +
                                  " cannot be removed (its folder is not writable or cannot be "
                                  "read); nothing was removed");
}

const std::vector<std::string>& run_file_names() {
  // summary.json first: clearing removes the mark of a complete folder before anything else.
  static const std::vector<std::string> names = {
      "summary.json", "summary.json.tmp", "energy.csv", "state.csv", "dummy.csv",
      "hands.csv",    "trace.csv",        "frames",    "event_trace", "restart_error.csv",
      "restart_error.csv.tmp"};
  return names;
}

std::vector<std::string> run_files_in(const fs::path& dir) {
  std::vector<std::string> present;
  std::error_code ec;
  for (const auto& name : run_file_names())
    if (fs::exists(fs::symlink_status(dir / name, ec))) present.push_back(name);
  return present;
}

void check_run_folder(const fs::path& dir, bool overwrite) {
  if (dir.empty()) throw InputError("--out", "", "is empty: name the output folder");
  std::error_code ec;
  const auto status = fs::status(dir, ec);
  if (fs::exists(status)) {
    if (!fs::is_directory(status)) throw folder_error(dir, "exists and is not a folder");
    if (!writable_folder(dir)) throw folder_error(dir, "the folder is not writable");
    const auto present = run_files_in(dir);
    if (!present.empty() && !overwrite)
      throw folder_error(dir, "holds another run's files (" + joined(present) +
                                  "); pass --overwrite to replace them, or choose another folder");
    check_removable(dir, present);
    return;
  }
  // The nearest existing ancestor must be a folder we may create entries in.
  fs::path target = fs::absolute(dir, ec).lexically_normal();
  if (!target.has_filename()) target = target.parent_path();  // "out/"
  fs::path parent = target.parent_path();
  while (!parent.empty() && !fs::exists(fs::status(parent, ec)) && parent != parent.root_path())
    parent = parent.parent_path();
  if (!fs::is_directory(fs::status(parent, ec)))
    throw folder_error(dir, "cannot be created: " + parent.string() + " is not a folder");
  if (!writable_folder(parent))
    throw folder_error(dir, "cannot be created: " + parent.string() + " is not writable");
  // Permissions do not tell everything (root, /proc, read-only mounts): create it and take it
  // back, so the check still changes nothing.
  fs::create_directories(dir, ec);
  if (ec) throw folder_error(dir, "cannot be created: " + ec.message());
  for (fs::path made = target; made != parent && made.has_relative_path();)
    fs::remove(std::exchange(made, made.parent_path()), ec);
}

void check_run_folder_not_experiment(const fs::path& dir) {
  std::error_code ec;
  if (fs::exists(fs::symlink_status(dir / "experiment.json", ec)))
    throw folder_error(dir, "holds an experiment (experiment.json): choose another folder");
}

std::vector<std::string> written_run_files(const nlohmann::json& summary, const std::string& file) {
  std::vector<std::string> names = {"energy.csv"};
  if (summary.contains("status") && summary["status"] == "ok") names.push_back("state.csv");
  if (summary_number(summary, file, "/object_particles") > 0.0) names.push_back("dummy.csv");
  const nlohmann::json::json_pointer input("/scene/input");
  if (summary.contains(input) && !summary[input].is_null()) names.push_back("hands.csv");
  if (summary_number(summary, file, "/scene/output/trace_interval") > 0.0)
    names.push_back("trace.csv");
  if (summary_number(summary, file, "/scene/output/event_trace_interval") > 0.0)
    for (const char* array : {"t", "x", "v", "fixed", "contact"})
      names.push_back(std::string("event_trace/") + array + ".npy");
  if (summary.contains("restart_error")) names.push_back("restart_error.csv");
  return names;
}

std::string rows_short_of_end(std::optional<double> last_t, const nlohmann::json& summary) {
  const auto number = [&](const char* pointer, double fallback) {
    const nlohmann::json::json_pointer at(pointer);
    return summary.contains(at) && summary[at].is_number() &&
                   std::isfinite(summary[at].get<double>())
               ? summary[at].get<double>()
               : fallback;
  };
  const double end = number("/sim_time", std::nan(""));
  if (std::isnan(end)) return "";
  const double interval = number("/scene/output/energy_interval", 0.01);
  const double slack = interval + number("/step_max", 0.0) + 1e-9 * std::max(1.0, std::abs(end));
  if (last_t && *last_t >= end - slack) return "";
  return (last_t ? fmt::format("the rows end at t = {} s", *last_t) : std::string("no rows")) +
         fmt::format(", before the run's sim_time = {} s in summary.json (more than "
                     "output.energy_interval = {} s and a step): the file is cut",
                     end, interval);
}

void clear_run_folder(const fs::path& dir) {
  fs::create_directories(dir);
  for (const auto& name : run_file_names()) fs::remove_all(dir / name);
}

}  // namespace drape
