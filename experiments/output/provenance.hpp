#pragma once
// Where a result comes from: the build (version, git commit, build type, SUNDIALS) and the run
// (date, machine). summary.json, the results table and `drapelab --version` carry it, so a
// number in a report can be traced to the code and the computer that made it (docs/outputs.md,
// "Provenance").
#include <nlohmann/json.hpp>
#include <string>

namespace drape {

/// The build's fields: version, git_commit (`-dirty` when tracked files differed from HEAD at
/// build time, `unknown` outside git), build_type, sundials_version.
nlohmann::json build_provenance();
/// The machine running now: {"hostname", "cpu" (model name from /proc/cpuinfo), "cores"}.
nlohmann::json machine_provenance();
/// The current time in UTC, ISO 8601 to the second (2026-11-23T22:01:23Z).
std::string utc_timestamp();
/// Build fields plus `date` (now) and `machine`: the provenance of a run started now.
nlohmann::json run_provenance();
/// The text of `drapelab --version`: one `key: value` line per field of run_provenance().
std::string version_text();

}  // namespace drape
