#pragma once
// The viewer's HTML page: the template with its CSS, three.js, its scripts and the runs' data
// inlined, so that it opens from file:// with no network (docs/viewer.md).
#include <string>
#include <vector>

#include "experiments/viewer/viewer_run.hpp"

namespace drape {

/// The whole page for these runs, shown side by side in this order.
std::string viewer_page(const std::vector<ViewerRun>& runs);

/// three.min.js and OrbitControls.js as two <script> elements (compiled in, else read at run
/// time; throws InputError naming the missing file), for this page and the live page.
std::string three_js_scripts();
/// `page` with the first `mark` replaced by `text` (a mark missing from a template is a bug).
void replace_mark(std::string& page, const std::string& mark, const std::string& text);
/// `code` as a <script> element.
std::string script(const std::string& code);

/// Text that can stand inside a <script> element: every "</" becomes "<\/" (JSON and JS
/// read both the same inside strings).
std::string script_safe(std::string text);

}  // namespace drape
