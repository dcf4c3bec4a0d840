#include "experiments/live/live_page.hpp"

#include "experiments/viewer/viewer_assets.hpp"
#include "experiments/viewer/viewer_page.hpp"

namespace drape {

namespace detail {
// Compiled in by CMake from live_page.html and live_main.js (experiments/live/CMakeLists.txt).
extern const std::string_view live_page_html;
extern const std::string_view live_main_js;
}  // namespace detail

std::string live_page(const std::string& scene_json) {
  std::string page(detail::live_page_html);
  // The viewer's style and scene code, so that the live picture is the viewer's.
  replace_mark(page, "<!-- drape:css -->",
               "<style>\n" + std::string(detail::viewer_css) + "</style>");
  replace_mark(page, "<!-- drape:data -->", script_safe(scene_json));
  replace_mark(page, "<!-- drape:three -->", three_js_scripts());
  replace_mark(page, "<!-- drape:scripts -->",
               script(std::string(detail::viewer_scene_js)) +
                   script(std::string(detail::viewer_ui_js)) +
                   script(std::string(detail::live_main_js)));
  return page;
}

}  // namespace drape
