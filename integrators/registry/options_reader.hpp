#pragma once
// The scene's `integrator` object read into IntegratorOptions and written back: the reader asks
// the registry which keys the named integrator declares.
#include <nlohmann/json.hpp>
#include <string>

#include "integrators/interface/integrator_options.hpp"

namespace drape {

/// Reads and validates an `integrator` object; errors name `file` and `path.key`.
IntegratorOptions read_integrator_options(const nlohmann::json& object, const std::string& file,
                                          const std::string& path);
/// The options as JSON, every key written (reproducibility).
nlohmann::json to_json(const IntegratorOptions& options);

}  // namespace drape
