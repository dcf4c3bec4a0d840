// The viewer's assets compiled in by CMake (experiments/viewer/CMakeLists.txt): each the bytes of
// its source file, as raw string literals must keep them; three.js either absent or the file
// CMake found.
#include "experiments/viewer/viewer_assets.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

namespace drape::detail {
namespace {

std::string bytes_of(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  EXPECT_TRUE(in) << file;
  return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(ViewerAssets, EachAssetIsItsSourceFileByteForByte) {
  const std::filesystem::path dir = std::filesystem::path(DRAPE_SOURCE_DIR) / "experiments" / "viewer";
  EXPECT_EQ(viewer_page_html, bytes_of(dir / "page.html"));
  EXPECT_EQ(viewer_css, bytes_of(dir / "viewer.css"));
  EXPECT_EQ(viewer_scene_js, bytes_of(dir / "viewer_scene.js"));
  EXPECT_EQ(viewer_ui_js, bytes_of(dir / "viewer_ui.js"));
  EXPECT_EQ(viewer_main_js, bytes_of(dir / "viewer_main.js"));
}

TEST(ViewerAssets, ThreeJsIsAbsentOrTheFileCMakeFound) {
  const std::filesystem::path dir(three_js_dir);
  if (!three_js.empty()) EXPECT_EQ(three_js, bytes_of(dir / "three.min.js"));
  if (!orbit_controls_js.empty())
    EXPECT_EQ(orbit_controls_js, bytes_of(dir / "examples" / "js" / "controls" / "OrbitControls.js"));
  EXPECT_EQ(three_js.empty(), orbit_controls_js.empty()) << "both or neither";
}

}  // namespace
}  // namespace drape::detail
