#pragma once
// The live mode's page (docs/viewer.md, "Live mode").
#include <string>

namespace drape {

/// The HTML page `drapelab live` serves at "/": it follows GET /events and posts keys to /key.
const std::string& live_page();

}  // namespace drape
