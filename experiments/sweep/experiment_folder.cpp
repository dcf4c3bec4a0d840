#include "experiments/sweep/experiment_folder.hpp"

#include <fstream>
#include <nlohmann/json.hpp>
#include <vector>

#include "core/io/input_error.hpp"
#include "core/io/json_reader.hpp"
#include "experiments/output/run_folder.hpp"

namespace drape {

namespace fs = std::filesystem;

const std::vector<std::string>& experiment_file_names() {
  static const std::vector<std::string> names = {
      "experiment.json", "results.csv", "results.json", "summary.csv", "metrics.csv",
      "metrics.json",    "runs",        "shards",       "report"};
  return names;
}

const std::vector<std::string>& experiment_run_file_names() {
  using namespace experiment_run_file;
  static const std::vector<std::string> names = {identity, result, progress, bisection, probes};
  return names;
}

namespace {

// Why a folder holding the experiment.json `header` is not experiment `name`'s to resume: ""
// when it is. A damaged header is said to be one, not taken for another experiment's.
std::string header_conflict(const fs::path& header, const std::string& name) {
  if (const auto reason = unreadable_file_reason(header.string()))  // a FIFO would wait
    return "holds an experiment.json that cannot be read (" + *reason + ")";
  std::ifstream in(header);
  const nlohmann::json doc = nlohmann::json::parse(in, nullptr, false);
  if (doc.is_discarded()) return "holds an experiment.json that is not valid JSON (damaged?)";
  if (!doc.is_object() || !doc.contains("name") || !doc["name"].is_string())
    return "holds an experiment.json without a name (not one drapelab wrote)";
  const std::string other = doc["name"].get<std::string>();
  if (other == name) return "";
  return "holds the files of another experiment (experiment.json names '" + other + "', not '" +
         name + "')";
}

}  // namespace

void check_experiment_folder(const fs::path& dir, const std::string& name, bool overwrite) {
  check_run_folder(dir, overwrite);  // a file, an uncreatable folder, a run's files
  const fs::path header = dir / "experiment.json";
  std::error_code ec;
  if (overwrite) {  // clear_experiment_folder removes what is in the way, if it all can go
    check_removable(dir, experiment_file_names());
    return;
  }
  for (const char* folder : {"runs", "shards"}) {
    const fs::path path = dir / folder;
    if (fs::exists(fs::symlink_status(path, ec)) && !fs::is_directory(path, ec))
      throw InputError(dir.string(), "--out",
                       std::string("holds a file '") + folder +
                           "' where the experiment writes a folder; remove it, choose another "
                           "folder or pass --overwrite");
  }
  if (!fs::exists(fs::symlink_status(header, ec))) return;
  const std::string conflict = header_conflict(header, name);
  if (conflict.empty()) return;
  throw InputError(dir.string(), "--out",
                   conflict + "; pass --overwrite to replace them, or choose another folder");
}

void remove_results_table(const fs::path& dir) {
  for (const char* name : {"results.json", "results.csv", "summary.csv"}) fs::remove(dir / name);
}

void clear_experiment_folder(const fs::path& dir) {
  fs::create_directories(dir);
  for (const auto& name : experiment_file_names()) fs::remove_all(dir / name);
  clear_run_folder(dir);
}

}  // namespace drape
