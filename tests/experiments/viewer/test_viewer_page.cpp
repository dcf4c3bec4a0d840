#include <gtest/gtest.h>

#include "experiments/viewer/viewer_page.hpp"
#include "viewer_test_files.hpp"

namespace drape {
namespace {

TEST(ViewerPage, ScriptSafeEscapesClosingTags) {
  EXPECT_EQ(script_safe(R"({"name": "</script><b>"})"), R"({"name": "<\/script><b>"})");
  EXPECT_EQ(script_safe("a</</b"), "a<\\/<\\/b");
}

TEST(ViewerPage, EverythingInlinedNoMarksLeft) {
  const std::string page = viewer_page({read_viewer_run(testing::tiny_run("page"))});
  EXPECT_EQ(page.find("<!-- drape:"), std::string::npos);
  EXPECT_NE(page.find("id=\"drape-data\""), std::string::npos);
  EXPECT_NE(page.find("OrbitControls"), std::string::npos);
  EXPECT_NE(page.find("drape.RunView"), std::string::npos);
  // No network: no script or stylesheet is loaded from elsewhere.
  EXPECT_EQ(page.find("<script src"), std::string::npos);
  EXPECT_EQ(page.find("<link"), std::string::npos);
}

}  // namespace
}  // namespace drape
