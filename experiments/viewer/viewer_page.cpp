#include "experiments/viewer/viewer_page.hpp"

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "core/io/input_error.hpp"
#include "experiments/viewer/page_data.hpp"
#include "experiments/viewer/viewer_assets.hpp"

namespace drape {

namespace fs = std::filesystem;

namespace {

// three.js as compiled in, else read now from DRAPE_THREE_JS_DIR or CMake's folder.
std::string three_file(std::string_view compiled, const std::string& relative) {
  if (!compiled.empty()) return std::string(compiled);
  const char* env = std::getenv("DRAPE_THREE_JS_DIR");
  const fs::path file = fs::path(env && *env ? env : std::string(detail::three_js_dir)) / relative;
  std::ifstream in(file);
  if (!in)
    throw InputError(file.string(), "",
                     "cannot read three.js for the page (Debian: apt install libjs-three, or set "
                     "DRAPE_THREE_JS_DIR to a folder with three.min.js and "
                     "examples/js/controls/OrbitControls.js)");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

void replace_mark(std::string& page, const std::string& mark, const std::string& text) {
  const size_t at = page.find(mark);
  if (at == std::string::npos) throw std::logic_error("the page template has no mark " + mark);
  page.replace(at, mark.size(), text);
}

std::string script(const std::string& code) { return "<script>\n" + code + "\n</script>\n"; }

std::string three_js_scripts() {
  // One after the other, so that a missing three.min.js is the file named.
  const std::string three = three_file(detail::three_js, "three.min.js");
  const std::string orbit =
      three_file(detail::orbit_controls_js, "examples/js/controls/OrbitControls.js");
  return script(three) + script(orbit);
}

std::string script_safe(std::string text) {
  for (size_t at = text.find("</"); at != std::string::npos; at = text.find("</", at + 3))
    text.replace(at, 2, "<\\/");
  return text;
}

std::string viewer_page(const std::vector<ViewerRun>& runs) {
  nlohmann::json data = {{"runs", nlohmann::json::array()}};
  for (const ViewerRun& run : runs) data["runs"].push_back(page_data(run));
  std::string page(detail::viewer_page_html);
  replace_mark(page, "<!-- drape:css -->",
               "<style>\n" + std::string(detail::viewer_css) + "</style>");
  replace_mark(page, "<!-- drape:three -->", three_js_scripts());
  replace_mark(page, "<!-- drape:scripts -->",
               script(std::string(detail::viewer_scene_js)) +
                   script(std::string(detail::viewer_ui_js)) +
                   script(std::string(detail::viewer_main_js)));
  replace_mark(page, "<!-- drape:data -->",
               "<script type=\"application/json\" id=\"drape-data\">" + script_safe(data.dump()) +
                   "</script>");
  return page;
}

}  // namespace drape
