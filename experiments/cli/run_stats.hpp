#pragma once
// The block `drapelab run` prints at the end of a run, in the manner of SUNDIALS' examples
// (ARKStepPrintAllStats): status, steps asked and taken, work counters, energy drift, wall time.
#include <nlohmann/json.hpp>
#include <string>

namespace drape {

/// The stats block of a run's summary.json, one counter a line.
std::string format_run_stats(const nlohmann::json& summary);

}  // namespace drape
