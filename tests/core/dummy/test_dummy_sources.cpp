#include "core/dummy/dummy_sources.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/dummy/dress_form.hpp"
#include "core/io/input_error.hpp"

namespace drape {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

constexpr double kPi = 3.141592653589793238462643383279;

DummySections sections_of(const json& spec, const fs::path& dir = {}) {
  return make_dummy_sections(spec, "scene.json", "dummy", dir);
}

// Expects an InputError whose field is `field` and whose message names it.
void expect_input_error(const json& spec, const std::string& field, const fs::path& dir = {}) {
  try {
    sections_of(spec, dir);
    ADD_FAILURE() << "no InputError for " << spec.dump();
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "scene.json") << e.what();
    EXPECT_EQ(e.field(), field) << e.what();
    EXPECT_NE(std::string(e.what()).find("scene.json: " + field + ": "), std::string::npos)
        << e.what();
  }
}

// Heights a rounding error apart pass the spec's checks and become equal when resampled: still
// an input error naming the dummy, not exit 1, "failed".
TEST(DummySources, SectionsEqualAfterResamplingAreAnInputError) {
  try {
    make_dummy({{"builtin", "cylinder"}, {"radius", 0.1}, {"y_top", 1.0}, {"y_bottom", 0.9999999999999999}},
               "scene.json", "dummy", {});
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "scene.json");
    EXPECT_EQ(e.field(), "dummy");
    EXPECT_NE(std::string(e.what()).find("strictly decrease"), std::string::npos) << e.what();
  }
}

// A scratch directory for sections files, removed with the fixture.
class SectionsFile : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    m_dir = fs::temp_directory_path() / (std::string("drape_test_dummy_sources_") + info->name());
    fs::create_directories(m_dir);
  }
  void TearDown() override { fs::remove_all(m_dir); }
  void write(const std::string& name, const std::string& text) const {
    std::ofstream(m_dir / name) << text;
  }
  fs::path m_dir;
};

TEST(DummySources, DefaultIsTheDressFormAtThePaperResolution) {
  const DummySections s = sections_of(json::object());
  EXPECT_EQ(s.num_sections(), 80);
  EXPECT_EQ(s.points(), 32);
  EXPECT_NEAR(s.y.front(), 1.345, 1e-12);
  EXPECT_NEAR(s.y.back(), 0.755, 1e-12);
  const DummySections named = sections_of({{"builtin", "dress-form"}});
  EXPECT_EQ(named.y, s.y);
  EXPECT_EQ(named.radius, s.radius);
  const DummySections coarse = sections_of({{"sections", 20}, {"points", 12}});
  EXPECT_EQ(coarse.num_sections(), 20);
  EXPECT_EQ(coarse.points(), 12);
}

TEST(DummySources, CylinderFollowsTheSpecFormula) {
  const DummySections s = sections_of({{"builtin", "cylinder"},
                                       {"radius", 0.12},
                                       {"center", {0.1, -0.05}},
                                       {"y_top", 1.4},
                                       {"y_bottom", 0.8},
                                       {"sections", 7},
                                       {"points", 10}});
  ASSERT_EQ(s.num_sections(), 7);
  ASSERT_EQ(s.points(), 10);
  for (int k = 0; k < 7; ++k) {
    EXPECT_DOUBLE_EQ(s.y[k], 1.4 - k * (1.4 - 0.8) / 6);
    EXPECT_EQ(s.cx[k], 0.1);
    EXPECT_EQ(s.cz[k], -0.05);
  }
  EXPECT_TRUE((s.radius.array() == 0.12).all());
}

TEST(DummySources, SphereSectionsAvoidThePoles) {
  const double R = 0.25;
  const Vec3 c(0.1, 1.1, -0.2);
  const Dummy dummy = make_dummy({{"builtin", "sphere"},
                                  {"radius", R},
                                  {"center", {c.x(), c.y(), c.z()}},
                                  {"sections", 9},
                                  {"points", 12}},
                                 "scene.json", "dummy", {});
  const DummySections& s = dummy.sections();
  for (int k = 0; k < 9; ++k) {
    const double phi = kPi * (k + 0.5) / 9;
    EXPECT_NEAR(s.y[k], c.y() + R * std::cos(phi), 1e-15);
    EXPECT_NEAR(s.radius(k, 0), R * std::sin(phi), 1e-15);
  }
  EXPECT_NEAR(s.y[4], c.y(), 1e-15);  // the equator for an odd count
  for (int o = 0; o < dummy.size(); ++o)
    EXPECT_NEAR((dummy.position(o) - c).norm(), R, 1e-15);
}

TEST(DummySources, ScaleThenOffsetPlaceAnySource) {
  const json cylinder = {{"builtin", "cylinder"}, {"radius", 0.1}, {"center", {0.2, 0.3}},
                         {"y_top", 1.0},          {"y_bottom", 0.5}};
  json placed = cylinder;
  placed["scale"] = 2.0;
  placed["offset"] = {1.0, -0.5, 0.25};
  const DummySections a = sections_of(cylinder), b = sections_of(placed);
  for (int k = 0; k < a.num_sections(); ++k) {
    EXPECT_NEAR(b.y[k], 2.0 * a.y[k] - 0.5, 1e-15);
    EXPECT_NEAR(b.cx[k], 2.0 * 0.2 + 1.0, 1e-15);
    EXPECT_NEAR(b.cz[k], 2.0 * 0.3 + 0.25, 1e-15);
  }
  EXPECT_TRUE((b.radius.array() == 0.2).all());

  const DummySections form = sections_of({{"scale", 0.5}, {"offset", {0.0, 0.1, 0.0}}});
  EXPECT_NEAR(form.y.front(), 0.5 * 1.345 + 0.1, 1e-12);
  EXPECT_NEAR(form.radius(0, 0), 0.5 * dress_form_sections(80, 32).radius(0, 0), 1e-15);
}

TEST_F(SectionsFile, IsResampledLinearlyInHeightAndAngle) {
  // Radii grow by 0.2 per metre downwards; the four rays alternate 0.1 / 0.2 (+ growth).
  write("form.json", R"({"sections": [
      {"y": 1.0, "center": [0.0, 0.0], "radii": [0.1, 0.2, 0.1, 0.2]},
      {"y": 0.5, "center": [0.1, 0.0], "radii": [0.2, 0.3, 0.2, 0.3]},
      {"y": 0.0, "center": [0.2, 0.1], "radii": [0.3, 0.4, 0.3, 0.4]}]})");
  const DummySections s =
      sections_of({{"file", "form.json"}, {"sections", 5}, {"points", 8}}, m_dir);
  ASSERT_EQ(s.num_sections(), 5);
  ASSERT_EQ(s.points(), 8);
  for (int k = 0; k < 5; ++k) {
    const double y = 1.0 - 0.25 * k;
    EXPECT_NEAR(s.y[k], y, 1e-15);
    EXPECT_NEAR(s.cx[k], 0.2 * (1.0 - y), 1e-15);
    EXPECT_NEAR(s.cz[k], y < 0.5 ? 0.2 * (0.5 - y) : 0.0, 1e-15);
    for (int j = 0; j < 8; ++j) {
      const double base = j % 2 ? 0.15 : (j % 4 == 0 ? 0.1 : 0.2);
      EXPECT_NEAR(s.radius(k, j), base + 0.2 * (1.0 - y), 1e-15) << k << " " << j;
    }
  }
  // an absolute path needs no base directory
  EXPECT_EQ(sections_of({{"file", (m_dir / "form.json").string()}, {"sections", 5}, {"points", 8}})
                .radius,
            s.radius);
}

TEST(DummySources, BadSceneInputNamesTheField) {
  const json cylinder = {{"builtin", "cylinder"}, {"radius", 0.1}, {"y_top", 1.0},
                         {"y_bottom", 0.5}};
  auto with = [&](const std::string& key, const json& value) {
    json spec = cylinder;
    spec[key] = value;
    return spec;
  };
  expect_input_error(with("radiuss", 0.1), "dummy.radiuss");
  expect_input_error(with("radius", -0.1), "dummy.radius");
  expect_input_error(with("radius", "big"), "dummy.radius");
  expect_input_error(with("sections", 1), "dummy.sections");
  expect_input_error(with("sections", 2.5), "dummy.sections");
  expect_input_error(with("points", 2), "dummy.points");
  expect_input_error(with("points", 1000000), "dummy.sections");
  expect_input_error(with("y_top", 0.5), "dummy.y_top");
  expect_input_error(with("center", {0.0, 0.0, 0.0}), "dummy.center");
  expect_input_error(with("scale", 0.0), "dummy.scale");
  expect_input_error(with("scale", 1e-300), "dummy.scale");  // hung in the nearest-particle grid
  expect_input_error(with("offset", {1.0, 2.0}), "dummy.offset");
  expect_input_error(with("file", "form.json"), "dummy.file");
  expect_input_error({{"builtin", "cylinder"}, {"radius", 0.1}, {"y_top", 1.0}},
                     "dummy.y_bottom");
  expect_input_error({{"builtin", "cube"}}, "dummy.builtin");
  expect_input_error({{"builtin", "sphere"}, {"radius", 0.1}, {"y_top", 1.0}}, "dummy.y_top");
  expect_input_error({{"builtin", "dress-form"}, {"radius", 0.1}}, "dummy.radius");
  expect_input_error({{"mesh", "body.obj"}}, "dummy.mesh");
}

TEST_F(SectionsFile, BadFilesNameTheSceneFieldAndTheFileField) {
  write("not_json.json", "{\"sections\": [");
  write("one.json", R"({"sections": [{"y": 1.0, "radii": [0.1, 0.1, 0.1]}]})");
  write("ragged.json", R"({"sections": [{"y": 1.0, "radii": [0.1, 0.1, 0.1]},
                                       {"y": 0.5, "radii": [0.1, 0.1]}]})");
  write("upside_down.json", R"({"sections": [{"y": 0.5, "radii": [0.1, 0.1, 0.1]},
                                            {"y": 1.0, "radii": [0.1, 0.1, 0.1]}]})");
  write("negative.json", R"({"sections": [{"y": 1.0, "radii": [0.1, 0.1, 0.1]},
                                         {"y": 0.5, "radii": [0.1, -0.1, 0.1]}]})");
  write("high.json", R"({"sections": [{"y": 1e7, "radii": [0.1, 0.1, 0.1]},
                                     {"y": 0.5, "radii": [0.1, 0.1, 0.1]}]})");
  write("far.json", R"({"sections": [{"y": 1.0, "radii": [0.1, 0.1, 0.1], "center": [0, -2e6]},
                                    {"y": 0.5, "radii": [0.1, 0.1, 0.1]}]})");
  write("wide.json", R"({"sections": [{"y": 1.0, "radii": [0.1, 0.1, 0.1]},
                                     {"y": 0.5, "radii": [0.1, 2000, 0.1]}]})");
  write("extra.json", R"({"sections": [{"y": 1.0, "radii": [0.1, 0.1, 0.1], "r": 1},
                                      {"y": 0.5, "radii": [0.1, 0.1, 0.1]}]})");
  const std::pair<const char*, const char*> cases[] = {
      {"missing.json", "no such file"},
      {"not_json.json", "not valid JSON"},
      {"one.json", "sections: expected an array of at least 2"},
      {"ragged.json", "sections[1].radii: expected 3 radii"},
      {"upside_down.json", "sections[1].y: must be below"},
      {"negative.json", "sections[1].radii: must not be negative"},
      {"extra.json", "sections[0].r: unknown key"},
      {"high.json", "sections[0].y: must be within +-1000000.0"},
      {"far.json", "sections[0].center: must be within +-1000000.0"},
      {"wide.json", "sections[1].radii: must be at most 1000.0"},
  };
  for (const auto& [name, what] : cases) {
    SCOPED_TRACE(name);
    expect_input_error({{"file", name}}, "dummy.file", m_dir);
    try {
      sections_of({{"file", name}}, m_dir);
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace drape
