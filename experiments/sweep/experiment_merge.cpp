#include "experiments/sweep/experiment_merge.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <map>
#include <set>
#include <nlohmann/json.hpp>

#include "core/io/input_error.hpp"
#include "experiments/output/run_files.hpp"
#include "experiments/sweep/experiment_folder.hpp"
#include "experiments/sweep/results_table.hpp"
#include "experiments/sweep/stored_runs.hpp"

namespace drape {

namespace fs = std::filesystem;

namespace {

// The fields merge and resume read from a folder's experiment.json, each of its type: a
// folder written by drapelab has them; a damaged or crafted one is named, field by field,
// instead of failing in the middle of the merge. A plan id names a folder under runs/, so it
// must be one plain name (a "../x" id made merge remove a folder outside DIR).
void check_header(const nlohmann::json& header, const std::string& file) {
  const auto require = [&](const char* key, bool ok, const char* expected) {
    if (!ok) throw InputError(file, key, std::string("expected ") + expected);
  };
  const auto strings = [](const nlohmann::json& j) {
    return j.is_array() && std::all_of(j.begin(), j.end(), [](const auto& e) { return e.is_string(); });
  };
  require("name", header.contains("name") && header["name"].is_string(), "a string");
  require("question", header.contains("question") && header["question"].is_string(), "a string");
  require("metrics", header.contains("metrics") && strings(header["metrics"]), "a list of strings");
  require("parameters", header.contains("parameters") && strings(header["parameters"]),
          "a list of strings");
  require("plan_size", header.contains("plan_size") && header["plan_size"].is_number_unsigned(),
          "a count");
  const nlohmann::json& plan = header["plan"];
  require("plan", plan.is_array(), "a list of runs");
  // The report reads plan_size to tell a finished experiment from a partial merge.
  if (header["plan_size"] != plan.size())
    throw InputError(file, "plan_size",
                     fmt::format("{} differs from the plan's {} runs", header["plan_size"].dump(),
                                 plan.size()));
  for (std::size_t k = 0; k < plan.size(); ++k) {
    const std::string field = fmt::format("plan[{}]", k);
    if (!plan[k].is_object() || !plan[k].contains("reference"))
      throw InputError(file, field, "expected a run of the plan (an object with id and reference)");
    const nlohmann::json& id = plan[k].value("id", nlohmann::json());
    if (!id.is_string() || id.get<std::string>().empty() || id == "." || id == ".." ||
        id.get<std::string>().find_first_of(std::string("/\\\0", 3)) != std::string::npos)
      throw InputError(file, field + ".id", "expected a run folder's name (no path): " + id.dump());
  }
}

nlohmann::json read_header(const fs::path& dir) {
  const fs::path file = dir / "experiment.json";
  auto header = read_json_if_present(file);
  if (!header || !header->contains("plan"))
    throw InputError(file.string(), "", "not an experiment output folder (no plan)");
  check_header(*header, file.string());
  return *header;
}

std::vector<std::string> plan_ids(const nlohmann::json& header) {
  std::vector<std::string> ids;
  for (const auto& run : header["plan"]) ids.push_back(run["id"].get<std::string>());
  return ids;
}

// The first key of the header of `source` that differs from `ours`, or "": two folders are of
// one experiment when everything but the definition's path (shards run on other machines) is
// the same; equal plans alone would merge another experiment's runs of the same values.
std::string header_difference(const nlohmann::json& source, const nlohmann::json& ours) {
  for (const char* key : {"name", "question", "metrics", "parameters", "experiment", "plan"})
    if (source.value(key, nlohmann::json()) != ours.value(key, nlohmann::json())) return key;
  return "";
}

// The first field in which two results of one run differ, or "": the machine, the build and the
// wall and CPU time may (a run repeated elsewhere), the outcome may not: two folders with different
// results of one run (overlapping shards, an edited result.json) are refused, not merged by
// keeping the first without a word.
std::string result_difference(const nlohmann::json& a, const nlohmann::json& b) {
  static const std::set<std::string> may_differ = {
      "wall_seconds", "cpu_seconds", "date",       "machine.hostname", "machine.cpu",
      "machine.cores", "git_commit", "version", "build_type",       "sundials_version"};
  for (const nlohmann::json* row : {&a, &b})
    for (const auto& item : row->items())
      if (!may_differ.count(item.key()) &&
          a.value(item.key(), nlohmann::json()) != b.value(item.key(), nlohmann::json()))
        return item.key();
  return "";
}

// Throws InputError naming the first entry of the run folder `dir` that is neither a file nor a
// folder: a named pipe (or a device, a socket) cannot be copied, and reading one would wait for
// a writer for ever.
void check_copyable(const fs::path& dir) {
  std::error_code ec;
  for (fs::recursive_directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const fs::file_status status = it->status(ec);
    if (!ec && !fs::is_regular_file(status) && !fs::is_directory(status))
      throw InputError(it->path().string(), "",
                       "not a regular file (merge copies the run's files)");
  }
  if (ec) throw InputError(dir.string(), "", "cannot be read: " + ec.message());
}

}  // namespace

std::vector<std::string> merge_results(const fs::path& out_dir, const std::vector<fs::path>& sources) {
  if (!fs::exists(out_dir / "experiment.json") && !sources.empty()) {
    const nlohmann::json first = read_header(sources.front());  // before DIR exists: no empty folder
    std::error_code ec;
    fs::create_directories(out_dir, ec);
    if (ec || !fs::is_directory(out_dir))
      throw InputError(out_dir.string(), "DIR",
                       "cannot be created: " + (ec ? ec.message() : std::string("not a folder")));
    write_json(out_dir / "experiment.json", first, process_tmp_suffix());
  }
  const nlohmann::json header = read_header(out_dir);
  const std::vector<std::string> ids = plan_ids(header);
  // Why a source's copy of a run was not taken (a damaged result.json): said with the run when
  // no source gives it, so that a damaged shard does not read as one not yet run.
  std::map<std::string, std::vector<std::string>> source_problems;
  for (const fs::path& source : sources) {
    if (fs::equivalent(source, out_dir)) continue;
    const std::string differs = header_difference(read_header(source), header);
    if (!differs.empty())
      throw InputError((source / "experiment.json").string(), differs,
                       "differs from " + (out_dir / "experiment.json").string() +
                           ": not a folder of the same experiment");
    for (std::size_t k = 0; k < ids.size(); ++k) {
      const std::string& id = ids[k];
      const fs::path from = source / "runs" / id, to = out_dir / "runs" / id;
      const StoredResult found = finished_run(from, header["plan"][k]);
      if (!found.row && !found.problem.empty()) source_problems[id].push_back(found.problem);
      if (!found.row) continue;
      if (const StoredResult there = finished_run(to, header["plan"][k]); there.row) {
        const std::string field = result_difference(*found.row, *there.row);
        if (!field.empty())
          throw InputError((from / experiment_run_file::result).string(), field,
                           "differs from " + (to / experiment_run_file::result).string() +
                               ", which is merged already: two results of one run (overlapping "
                               "shards, or an edited file); remove the wrong one");
        continue;
      }
      check_run_files(from, *found.row);  // a damaged run is named, not copied
      check_copyable(from);
      fs::remove_all(to);
      fs::create_directories(to.parent_path());
      try {
        fs::copy(from, to, fs::copy_options::recursive);
      } catch (const fs::filesystem_error& e) {
        // A full disk: the half-copied run is removed, so that it is not taken as finished.
        std::error_code ignored;
        fs::remove_all(to, ignored);
        throw OutputError("cannot copy " + from.string() + " to " + to.string() + ": " +
                          e.code().message());
      }
    }
  }
  std::vector<nlohmann::json> rows;
  std::vector<std::string> missing;
  for (std::size_t k = 0; k < ids.size(); ++k) {
    auto [row, problem] = finished_run(out_dir / "runs" / ids[k], header["plan"][k]);
    if (!row) {
      std::vector<std::string> why = source_problems[ids[k]];
      if (!problem.empty()) why.insert(why.begin(), problem);
      missing.push_back(why.empty() ? ids[k] : fmt::format("{}: {}", ids[k], fmt::join(why, "; ")));
      continue;
    }
    check_run_files(out_dir / "runs" / ids[k], *row);
    (*row)["index"] = static_cast<int>(k);
    (*row)["reference"] = header["plan"][k]["reference"];
    rows.push_back(std::move(*row));
  }
  write_results_table(out_dir / "results", header, rows, "");
  return missing;
}

}  // namespace drape
