#pragma once
// The viewer's HTML page: the template with its CSS, three.js, its scripts and the runs' data
// inlined, so that it opens from file:// with no network (docs/viewer.md).
#include <string>
#include <vector>

#include "experiments/viewer/viewer_run.hpp"

namespace drape {

/// The whole page for these runs, shown side by side in this order.
std::string viewer_page(const std::vector<ViewerRun>& runs);

/// Text that can stand inside a <script> element: every "</" becomes "<\/" (JSON and JS
/// read both the same inside strings).
std::string script_safe(std::string text);

}  // namespace drape
