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
/// The CSV columns of some rows: identity, parameters (in plan order), known metrics, the rest.
std::vector<std::string> result_columns(const std::vector<std::string>& parameters,
                                        const std::vector<nlohmann::json>& rows);
/// Writes rows as CSV with the given columns (JSON values dumped, strings quoted when needed).
void write_results_csv(const std::filesystem::path& file, const std::vector<std::string>& columns,
                       const std::vector<nlohmann::json>& rows);
/// Writes JSON to a temporary file and renames it, so readers never see half a file.
void write_json_atomic(const std::filesystem::path& file, const nlohmann::json& value);

}  // namespace drape
