#pragma once
// `drapelab fabrics`: the fabric presets with their sources (docs/fabrics.md).

namespace drape {

/// Prints every fabric preset as a table, or as a JSON list with `json`. Returns exit status 0.
int list_fabrics(bool json);

}  // namespace drape
