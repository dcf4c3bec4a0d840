#pragma once
// The viewer page's assets, compiled in by CMake (experiments/viewer/CMakeLists.txt).
#include <string_view>

namespace drape::detail {
extern const std::string_view viewer_page_html;  ///< page.html, with the insertion marks
extern const std::string_view viewer_css;
extern const std::string_view viewer_scene_js;
extern const std::string_view viewer_ui_js;
extern const std::string_view viewer_main_js;
/// three.min.js and OrbitControls.js of libjs-three; empty when not found at configure time.
extern const std::string_view three_js;
extern const std::string_view orbit_controls_js;
/// Where CMake looked for them (the run-time fallback's default).
extern const std::string_view three_js_dir;
}  // namespace drape::detail
