#pragma once
// The results table of an experiment: one row per run with every parameter and every metric the
// runner knows from summary.json, written as CSV and JSON (docs/experiments.md).
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "experiments/sweep/experiment.hpp"

namespace drape {

/// The row of a run from its summary.json (status, counters, energy drift, attach errors).
nlohmann::json result_row(const RunSpec& run, const nlohmann::json& summary);
/// The row of a run that could not run at all (status `error`, the message as reason).
nlohmann::json error_row(const RunSpec& run, const std::string& message);
/// Why `row`, read back from a run's result.json, is not a result of run `id` (empty when it
/// is): it must be an object whose `id` is `id`, whose `run_dir` is `runs/<id>` and whose
/// `status` is one of ok, diverged, failed, error and crashed.
std::string result_row_problem(const nlohmann::json& row, const std::string& id);
/// The CSV columns of some rows: identity, parameters (in plan order), known metrics, the rest.
std::vector<std::string> result_columns(const std::vector<std::string>& parameters,
                                        const std::vector<nlohmann::json>& rows);
/// Writes rows as CSV with the given columns (JSON values dumped, strings quoted when needed).
void write_results_csv(const std::filesystem::path& file, const std::vector<std::string>& columns,
                       const std::vector<nlohmann::json>& rows);
/// Writes `stem`.json and `stem`.csv: the rows with the experiment.json `header`'s name,
/// question, metrics, parameters and plan size, and `shard` ("K/N", or "" for the whole plan);
/// a whole ensemble's (`repeats`) statistics per group go to summary.csv beside them.
void write_results_table(const std::filesystem::path& stem, const nlohmann::json& header,
                         const std::vector<nlohmann::json>& rows, const std::string& shard);
/// `.tmp.PID`: the temporary suffix (write_file_atomic) of the files that the shards of an
/// experiment, on one shared folder, write alike: each process its own temporary.
std::string process_tmp_suffix();

}  // namespace drape
