#include "experiments/sweep/results_table.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <unistd.h>

#include "experiments/output/run_files.hpp"
#include "experiments/sweep/ensemble_summary.hpp"

namespace drape {

namespace {

// Metric columns in the order a reader expects them; anything else follows, sorted.
const std::vector<std::string>& metric_columns() {
  static const std::vector<std::string> names = {
      "integrator", "table", "dt", "adaptive", "steps", "rhs_evals", "wall_seconds", "cpu_seconds",
      "sim_time", "duration", "time", "particles", "springs", "object_particles", "energy_initial",
      "energy_final", "energy_drift_max_abs", "energy_drift_max_rel", "energy_drift_final_rel",
      "energy_rise_max_rel", "events", "hold_count", "release_count", "map_count",
      "ignored_count", "attach_count",
      "attach_error_mean", "attach_error_max", "bisect_parameter", "stable_value",
      "unstable_value", "probes", "version", "git_commit", "build_type", "sundials_version",
      "date", "machine.hostname", "machine.cpu", "machine.cores"};
  return names;
}

const std::vector<std::string>& identity_columns() {
  static const std::vector<std::string> names = {"index", "id", "scene", "status", "reason",
                                                 "is_reference", "reference", "run_dir"};
  return names;
}

nlohmann::json identity(const RunSpec& run, const std::string& status) {
  nlohmann::json row = {{"index", run.index},   {"id", run.id},
                        {"scene", run.scene},   {"status", status},
                        {"reason", ""},         {"is_reference", run.is_reference},
                        {"reference", run.reference}, {"run_dir", "runs/" + run.id}};
  for (const auto& [key, value] : run.parameters) row[key] = value;
  return row;
}

std::string csv_cell(const nlohmann::json& value) {
  if (value.is_null()) return "";
  std::string text = value.is_string() ? value.get<std::string>() : value.dump();
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (const char ch : text) quoted += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return quoted + "\"";
}

}  // namespace

nlohmann::json result_row(const RunSpec& run, const nlohmann::json& summary) {
  nlohmann::json row = identity(run, summary.value("status", "error"));
  row["reason"] = summary.value("reason", "");
  for (const char* key : {"integrator", "table", "dt", "adaptive", "steps", "rhs_evals",
                          "wall_seconds", "cpu_seconds", "sim_time", "duration", "time", "particles",
                          "springs", "object_particles", "energy_initial", "energy_final",
                          "energy_drift_max_abs", "energy_drift_max_rel", "energy_rise_max_rel"})
    if (summary.contains(key)) row[key] = summary[key];
  const double e0 = summary.value("energy_initial", 0.0);
  const double e1 = summary.value("energy_final", 0.0);
  row["energy_drift_final_rel"] = std::abs(e1 - e0) / std::max(std::abs(e0), 1e-300);
  // Provenance (docs/outputs.md): the build and machine of each run, as its own columns.
  for (const char* key : {"version", "git_commit", "build_type", "sundials_version", "date"})
    if (summary.contains(key)) row[key] = summary[key];
  if (summary.contains("machine"))
    for (const auto& item : summary["machine"].items()) row["machine." + item.key()] = item.value();
  if (summary.contains("counters"))
    for (const auto& item : summary["counters"].items()) row["counters." + item.key()] = item.value();

  int attach = 0, hold = 0, release = 0, map = 0, ignored = 0;
  double attach_sum = 0.0, attach_max = 0.0;
  const nlohmann::json events = summary.value("events", nlohmann::json::array());
  for (const auto& e : events) {
    const std::string type = e.value("type", "");
    hold += type == "hold";
    release += type == "release";
    map += type == "map";
    ignored += type == "ignored";
    if (type == "attach_fixed" && e.contains("attach_error")) {
      const double err = e["attach_error"].get<double>();
      ++attach;
      attach_sum += err;
      attach_max = std::max(attach_max, err);
    }
  }
  row["events"] = events.size();
  row["hold_count"] = hold;
  row["release_count"] = release;
  row["map_count"] = map;
  row["ignored_count"] = ignored;
  row["attach_count"] = attach;
  row["attach_error_mean"] = attach > 0 ? nlohmann::json(attach_sum / attach) : nlohmann::json();
  row["attach_error_max"] = attach > 0 ? nlohmann::json(attach_max) : nlohmann::json();
  return row;
}

nlohmann::json error_row(const RunSpec& run, const std::string& message) {
  nlohmann::json row = identity(run, "error");
  row["reason"] = message;
  return row;
}

std::string result_row_problem(const nlohmann::json& row, const std::string& id) {
  if (!row.is_object()) return fmt::format("is a JSON {}, not an object", row.type_name());
  // The value of `key` as the file has it, for the message.
  auto found = [&](const char* key) {
    return row.contains(key) ? row[key].dump() : std::string("missing");
  };
  if (row.value("id", nlohmann::json()) != id)
    return fmt::format("\"id\" is {}, not the run's id \"{}\"", found("id"), id);
  if (row.value("run_dir", nlohmann::json()) != "runs/" + id)
    return fmt::format("\"run_dir\" is {}, not \"runs/{}\"", found("run_dir"), id);
  static const std::set<nlohmann::json> statuses = {"ok", "diverged", "failed", "error",
                                                     "crashed"};
  if (!statuses.count(row.value("status", nlohmann::json())))
    return fmt::format("\"status\" is {}, not one of ok, diverged, failed, error, crashed",
                       found("status"));
  return "";
}

std::vector<std::string> result_columns(const std::vector<std::string>& parameters,
                                        const std::vector<nlohmann::json>& rows) {
  std::vector<std::string> columns = identity_columns();
  columns.insert(columns.end(), parameters.begin(), parameters.end());
  std::set<std::string> present;
  for (const auto& row : rows)
    for (const auto& item : row.items()) present.insert(item.key());
  for (const auto& name : metric_columns())
    if (present.count(name) &&
        std::find(columns.begin(), columns.end(), name) == columns.end())
      columns.push_back(name);
  for (const auto& name : present)
    if (std::find(columns.begin(), columns.end(), name) == columns.end()) columns.push_back(name);
  return columns;
}

void write_results_csv(const std::filesystem::path& file, const std::vector<std::string>& columns,
                       const std::vector<nlohmann::json>& rows) {
  write_file_atomic(file, process_tmp_suffix(), [&](std::ostream& out) {
    for (std::size_t c = 0; c < columns.size(); ++c) out << (c ? "," : "") << csv_cell(columns[c]);
    out << "\n";
    for (const auto& row : rows) {
      for (std::size_t c = 0; c < columns.size(); ++c)
        out << (c ? "," : "") << (row.contains(columns[c]) ? csv_cell(row[columns[c]]) : "");
      out << "\n";
    }
  });
}

std::string process_tmp_suffix() { return fmt::format(".tmp.{}", ::getpid()); }

void write_results_table(const std::filesystem::path& stem, const nlohmann::json& header,
                 const std::vector<nlohmann::json>& rows, const std::string& shard) {
  const auto parameters = header["parameters"].get<std::vector<std::string>>();
  const auto columns = result_columns(parameters, rows);
  nlohmann::json doc = {{"name", header["name"]},       {"question", header["question"]},
                        {"metrics", header["metrics"]}, {"parameters", parameters},
                        {"plan_size", header["plan_size"]},
                        {"shard", shard.empty() ? nlohmann::json() : nlohmann::json(shard)},
                        {"columns", columns},           {"runs", rows}};
  write_json(stem.string() + ".json", doc, process_tmp_suffix());
  write_results_csv(stem.string() + ".csv", columns, rows);
  // An ensemble (`repeats`) also gets its statistics per group beside results.csv.
  if (shard.empty() &&
      std::find(parameters.begin(), parameters.end(), repeat_parameter) != parameters.end())
    write_ensemble_summary(stem.parent_path() / "summary.csv", parameters, rows);
}


}  // namespace drape
