#pragma once
// `drapelab fabrics`: the fabric presets with their sources (docs/fabrics.md).

#include <nlohmann/json.hpp>

namespace drape {

/// Every fabric preset with its source and units, as `drapelab fabrics --json` prints it.
nlohmann::json fabrics_json();

/// Prints every fabric preset as a table, or as a JSON list with `json`. Returns exit status 0.
int list_fabrics(bool json);

}  // namespace drape
