#include "core/dummy/mesh_sections.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/dummy/dummy_sources.hpp"
#include "core/io/input_error.hpp"

namespace drape {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

constexpr double kPi = 3.141592653589793238462643383279;

/// A vertical prism (or frustum): ring `bottom` (x, z) at y0 joined by quads to ring `top` at
/// y1, optionally closed by one polygon at each end. Returns OBJ text (1-based indices).
std::string prism_obj(const std::vector<Eigen::Vector2d>& bottom, double y0,
                      const std::vector<Eigen::Vector2d>& top, double y1, bool caps) {
  const int n = static_cast<int>(bottom.size());
  std::ostringstream obj;
  obj.precision(17);
  obj << "# generated prism\n";
  for (const auto& p : bottom) obj << "v " << p.x() << ' ' << y0 << ' ' << p.y() << '\n';
  for (const auto& p : top) obj << "v " << p.x() << ' ' << y1 << ' ' << p.y() << '\n';
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    obj << "f " << i + 1 << ' ' << j + 1 << ' ' << n + j + 1 << ' ' << n + i + 1 << '\n';
  }
  if (caps) {
    obj << "f";
    for (int i = n; i > 0; --i) obj << ' ' << i;
    obj << "\nf";
    for (int i = 1; i <= n; ++i) obj << ' ' << n + i;
    obj << '\n';
  }
  return obj.str();
}

/// A regular n-gon of circumradius r about c with a corner at theta = 0 (towards +z).
std::vector<Eigen::Vector2d> regular_polygon(int n, double r, const Eigen::Vector2d& c) {
  std::vector<Eigen::Vector2d> ring;
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * kPi * i / n;
    ring.push_back(c + r * Eigen::Vector2d(std::sin(a), std::cos(a)));
  }
  return ring;
}

/// A scratch directory for OBJ files, removed with the fixture.
class MeshSections : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    m_dir = fs::temp_directory_path() / (std::string("drape_test_mesh_sections_") + info->name());
    fs::create_directories(m_dir);
  }
  void TearDown() override { fs::remove_all(m_dir); }

  void write(const std::string& name, const std::string& text) const {
    std::ofstream(m_dir / name) << text;
  }
  DummySections sections_of(const json& spec) const {
    return make_dummy_sections(spec, "scene.json", "dummy", m_dir);
  }
  // Expects an InputError on `field` whose message names it and contains `what`.
  void expect_input_error(const json& spec, const std::string& field,
                          const std::string& what) const {
    try {
      sections_of(spec);
      ADD_FAILURE() << "no InputError for " << spec.dump();
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), "scene.json") << e.what();
      EXPECT_EQ(e.field(), field) << e.what();
      const std::string message = e.what();
      EXPECT_EQ(message.rfind("scene.json: " + field + ": ", 0), 0u) << message;
      EXPECT_NE(message.find(what), std::string::npos) << message;
    }
  }

  fs::path m_dir;
};

TEST_F(MeshSections, FacetedFrustumMatchesTheClosedForm) {
  // A 12-sided pyramid frustum: the slice at height y is a regular 12-gon of circumradius
  // R(y) = 0.3 - 0.2 y about c, and a ray at theta in the facet from corner a_i meets it at
  // R(y) cos(pi/12) / cos(theta - a_i - pi/12). Rays every 10 degrees also hit corners exactly.
  // The corners pass through tinyobjloader's float coordinates (the Debian library is built
  // with float), hence 1e-7 m rather than round-off; the other shapes have exact coordinates.
  const int n = 12;
  const Eigen::Vector2d c(0.1, -0.2);
  write("frustum.obj", prism_obj(regular_polygon(n, 0.3, c), 0.0, regular_polygon(n, 0.1, c),
                                 1.0, true));
  const DummySections s = sections_of({{"mesh", "frustum.obj"},
                                       {"y_top", 0.9},
                                       {"y_bottom", 0.1},
                                       {"sections", 5},
                                       {"points", 36}});
  ASSERT_EQ(s.num_sections(), 5);
  ASSERT_EQ(s.points(), 36);
  for (int k = 0; k < 5; ++k) {
    const double y = 0.9 - 0.2 * k;
    EXPECT_NEAR(s.y[k], y, 1e-15);
    EXPECT_NEAR(s.cx[k], c.x(), 1e-7);
    EXPECT_NEAR(s.cz[k], c.y(), 1e-7);
    const double r = 0.3 - 0.2 * y;
    for (int j = 0; j < 36; ++j) {
      const double theta = 2.0 * kPi * j / 36;
      const double corner = 2.0 * kPi / n * std::floor(theta / (2.0 * kPi / n));
      const double expected = r * std::cos(kPi / n) / std::cos(theta - corner - kPi / n);
      EXPECT_NEAR(s.radius(k, j), expected, 1e-7) << "k " << k << " j " << j;
    }
  }
}

TEST_F(MeshSections, BoxInCentimetresUsesTheUnitAndTheDefaultRange) {
  // A box 40 x 20 cm (x by z) about (5, -3) cm, from 50 to 150 cm; in metres the ray at theta
  // meets it at min(0.2 / |sin theta|, 0.1 / |cos theta|). By default the sections are
  // cell-centred in the mesh's height: y_k = 1.5 - (k + 1/2) 1.0 / 4.
  const std::vector<Eigen::Vector2d> ring = {{25, 7}, {25, -13}, {-15, -13}, {-15, 7}};
  write("box.obj", prism_obj(ring, 50.0, ring, 150.0, true));
  const DummySections s =
      sections_of({{"mesh", "box.obj"}, {"unit", 0.01}, {"sections", 4}, {"points", 16}});
  ASSERT_EQ(s.num_sections(), 4);
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(s.y[k], 1.5 - (k + 0.5) * 0.25, 1e-14);
    EXPECT_NEAR(s.cx[k], 0.05, 1e-14);
    EXPECT_NEAR(s.cz[k], -0.03, 1e-14);
    for (int j = 0; j < 16; ++j) {
      const double theta = 2.0 * kPi * j / 16;
      const double expected = std::min(std::abs(0.2 / std::sin(theta)),
                                       std::abs(0.1 / std::cos(theta)));
      EXPECT_NEAR(s.radius(k, j), expected, 1e-14) << "k " << k << " j " << j;
    }
  }
  // scale and offset place it like any source; an absolute path needs no base directory
  const DummySections placed =
      make_dummy_sections({{"mesh", (m_dir / "box.obj").string()},
                           {"unit", 0.01},
                           {"sections", 4},
                           {"points", 16},
                           {"scale", 2.0},
                           {"offset", {0.0, 1.0, 0.0}}},
                          "scene.json", "dummy", {});
  EXPECT_NEAR(placed.y[0], 2.0 * s.y[0] + 1.0, 1e-14);
  EXPECT_NEAR(placed.cx[0], 2.0 * s.cx[0], 1e-14);
  EXPECT_NEAR(placed.radius(0, 4), 2.0 * s.radius(0, 4), 1e-14);
}

TEST_F(MeshSections, CentreIsMidwayBetweenFrontAndBack) {
  // A trapezoid prism, 0.5 wide at the back (z = 0) and 0.25 at the front (z = 0.375): the
  // area centroid is at z = 0.375 (0.5 + 2 * 0.25) / (3 * 0.75) = 0.1667, but the centre is in
  // the middle of the front-back line, z = 0.1875, where the side rays meet the sides at
  // x = +-0.1875: every one of the four rays is 0.1875 long.
  const std::vector<Eigen::Vector2d> ring = {
      {0.125, 0.375}, {0.25, 0.0}, {-0.25, 0.0}, {-0.125, 0.375}};
  write("trapezoid.obj", prism_obj(ring, 0.0, ring, 1.0, true));
  const DummySections s = sections_of(
      {{"mesh", "trapezoid.obj"}, {"y_top", 0.5}, {"y_bottom", 0.4}, {"points", 4}});
  for (int k = 0; k < s.num_sections(); ++k) {
    EXPECT_NEAR(s.cx[k], 0.0, 1e-15);
    EXPECT_NEAR(s.cz[k], 0.1875, 1e-15);
    for (int j = 0; j < 4; ++j) EXPECT_NEAR(s.radius(k, j), 0.1875, 1e-15) << j;
  }
}

/// The rows of the reference CSV: height (cm), flag, centre (cm), 72 radii (cm).
struct CsvSection {
  double height_cm = 0.0;
  int flag = 0;
  double cx = 0.0, cz = 0.0;
  std::vector<double> radii;
};

std::vector<CsvSection> read_reference_csv(const std::string& file) {
  std::ifstream in(file);
  std::vector<CsvSection> rows;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line.rfind("height_cm", 0) == 0) continue;
    std::istringstream fields(line);
    std::vector<double> v;
    for (std::string f; std::getline(fields, f, ',');) v.push_back(std::stod(f));
    CsvSection row;
    row.height_cm = v[0];
    row.flag = static_cast<int>(v[1]);
    row.cx = v[2];
    row.cz = v[3];
    row.radii.assign(v.begin() + 6, v.end());
    rows.push_back(row);
  }
  return rows;
}

TEST(MeshSectionsBody, MatchesTheReferenceSlicingOfTheSameMesh) {
  // The built-in dress form's CSV is a slicing of this very OBJ (centre, then the nearest
  // surface hit along 72 rays). Slicing it here at the CSV's clean torso heights (flag 0,
  // 119.5 down to 75.5 cm) gives its centres and radii within 0.11 mm (median 3 um): its radii
  // follow quads fanned from their first corner, as here, but its centres agree to 5 um with
  // quads split along the shorter diagonal instead, and a centre 0.09 mm off moves the rays'
  // ends as much. Hence 0.2 mm. Splitting along the shorter diagonal here would leave 9 mm
  // errors where rays graze the crotch notch (77.5 cm, 30 degrees).
  const std::string data = std::string(DRAPE_SOURCE_DIR) + "/core/dummy/data/dress-form/";
  const std::vector<CsvSection> csv =
      read_reference_csv(data + "mh_default_female_torso_sections.csv");
  const DummySections s = make_dummy_sections({{"mesh", data + "mh_default_female_body_cm.obj"},
                                               {"unit", 0.01},
                                               {"y_top", 1.195},
                                               {"y_bottom", 0.755},
                                               {"sections", 45},
                                               {"points", 72}},
                                              "scene.json", "dummy", {});
  ASSERT_EQ(s.num_sections(), 45);
  int compared = 0;
  for (const CsvSection& row : csv) {
    if (row.flag != 0 || row.height_cm < 75.0 || row.height_cm > 120.0) continue;
    const int k = static_cast<int>(std::lround(119.5 - row.height_cm));
    SCOPED_TRACE("height " + std::to_string(row.height_cm) + " cm");
    EXPECT_NEAR(s.y[k], 0.01 * row.height_cm, 1e-12);
    EXPECT_NEAR(s.cx[k], 0.01 * row.cx, 2e-4);
    EXPECT_NEAR(s.cz[k], 0.01 * row.cz, 2e-4);
    for (int j = 0; j < 72; ++j) EXPECT_NEAR(s.radius(k, j), 0.01 * row.radii[j], 2e-4) << j;
    ++compared;
  }
  EXPECT_EQ(compared, 45);
}

TEST_F(MeshSections, BadInputNamesTheSceneFieldAndTheMeshFile) {
  const std::vector<Eigen::Vector2d> square = {{0.1, 0.1}, {0.1, -0.1}, {-0.1, -0.1},
                                               {-0.1, 0.1}};
  write("box.obj", prism_obj(square, 0.0, square, 1.0, true));
  write("garbage.obj", "this is not\n an OBJ file \x01\x02\n");
  write("bad_index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n");
  write("no_faces.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  write("nan.obj", "v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n");
  write("inf.obj", "v 0 0 0\nv 1 0 0\nv 0 1 1e999\nf 1 2 3\n");
  write("far.obj", "v 0 0 0\nv 1 0 0\nv 0 1 1e8\nf 1 2 3\n");
  write("far_km.obj", "v 0 0 0\nv 1e4 0 0\nv 0 1 0\nf 1 2 3\n");
  write("two_corners.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\nf 1 2 3\n");
  write("overflow.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999/1\n");
  write("most_negative.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -9223372036854775808\n");
  write("ahead.obj", "v 0 0 0\nv 1 0 0\nf 1 2 3\nv 0 1 0\n");
  write("short_vertex.obj", "v 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\n");
  write("bare_vertex.obj", "v 0 0 0\nv\nv 0 1 0\nf 1 2 3\n");
  write("flat.obj", "v 0 0.5 0\nv 1 0.5 0\nv 0 0.5 1\nf 1 2 3\n");
  // One vertical wall: every slice is a single segment enclosing nothing.
  write("wall.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
  // A U-shaped channel open towards +x: its area centroid lies in the hollow, and the ray from
  // there towards +x leaves through the opening.
  const std::vector<Eigen::Vector2d> u = {{0.1, 0.1},     {-0.1, 0.1},   {-0.1, -0.1},
                                          {0.1, -0.1},    {0.1, -0.08},  {-0.08, -0.08},
                                          {-0.08, 0.08},  {0.1, 0.08}};
  write("channel.obj", prism_obj(u, 0.0, u, 1.0, false));

  const json box = {{"mesh", "box.obj"}};
  auto with = [&](const std::string& key, const json& value) {
    json spec = box;
    spec[key] = value;
    return spec;
  };
  expect_input_error({{"mesh", "missing.obj"}}, "dummy.mesh", "missing.obj: no such file");
  expect_input_error({{"mesh", "/dev/zero"}}, "dummy.mesh", "/dev/zero: not a regular file");
  expect_input_error({{"mesh", "."}}, "dummy.mesh", ".: is a directory, not a file");
  expect_input_error({{"mesh", "garbage.obj"}}, "dummy.mesh", "garbage.obj: ");
  expect_input_error({{"mesh", "no_faces.obj"}}, "dummy.mesh", "no_faces.obj: the OBJ file has");
  expect_input_error({{"mesh", "nan.obj"}}, "dummy.mesh",
                     "nan.obj: line 3: vertex coordinate \"nan\" is not a finite number");
  expect_input_error({{"mesh", "inf.obj"}}, "dummy.mesh",
                     "inf.obj: line 3: vertex coordinate \"1e999\" is not a finite number");
  expect_input_error({{"mesh", "bad_index.obj"}}, "dummy.mesh",
                     "bad_index.obj: line 4: face corner \"7\" is not a vertex of the 3 before it");
  expect_input_error({{"mesh", "overflow.obj"}}, "dummy.mesh",
                     "overflow.obj: line 4: face corner \"99999999999/1\" is not a vertex of the 3 before it");
  expect_input_error({{"mesh", "most_negative.obj"}}, "dummy.mesh",
                     "most_negative.obj: line 4: face corner \"-9223372036854775808\" is not a vertex of the 3 before it");
  expect_input_error({{"mesh", "ahead.obj"}}, "dummy.mesh",
                     "ahead.obj: line 3: face corner \"3\" is not a vertex of the 2 before it");
  // tinyobjloader reads a missing coordinate as 0.
  expect_input_error({{"mesh", "short_vertex.obj"}}, "dummy.mesh",
                     "short_vertex.obj: line 2: a vertex of 2 coordinates (x y z needed)");
  expect_input_error({{"mesh", "bare_vertex.obj"}}, "dummy.mesh",
                     "bare_vertex.obj: line 2: a vertex of 0 coordinates (x y z needed)");
  // Said of the mesh, not of the y_top and y_bottom the user did not set.
  expect_input_error({{"mesh", "flat.obj"}}, "dummy.mesh",
                     "flat.obj: the mesh has no height: every vertex at y = 0.5 m after unit");
  expect_input_error({{"mesh", "two_corners.obj"}}, "dummy.mesh",
                     "two_corners.obj: line 4: a face of 2 corners (at least 3)");
  // 1e8 m, and 1e4 units of 1 km: beyond the scene's +-1e6 m.
  expect_input_error({{"mesh", "far.obj"}}, "dummy.mesh",
                     "far.obj: line 3: vertex coordinate 1e8 x unit 1 m is beyond +-1e+06 m");
  expect_input_error({{"mesh", "far_km.obj"}, {"unit", 1e3}}, "dummy.mesh",
                     "far_km.obj: line 2: vertex coordinate 1e4 x unit 1000 m is beyond +-1e+06 m");
  expect_input_error({{"mesh", "wall.obj"}}, "dummy.mesh", "no surface encloses a centre");
  expect_input_error({{"mesh", "channel.obj"}, {"points", 4}}, "dummy.mesh",
                     "the ray at theta = 90 deg");
  expect_input_error({{"mesh", 3}}, "dummy.mesh", "");
  expect_input_error(with("colour", "red"), "dummy.colour", "unknown key");
  expect_input_error(with("radius", 0.1), "dummy.radius", "unknown key");
  expect_input_error(with("unit", 0.0), "dummy.unit", "");
  expect_input_error(with("unit", -0.01), "dummy.unit", "");
  expect_input_error(with("unit", "cm"), "dummy.unit", "");
  expect_input_error(with("y_top", 1.5), "dummy.y_top", "below the mesh's top");
  expect_input_error(with("y_bottom", -0.5), "dummy.y_bottom", "above the mesh's bottom");
  json upside_down = with("y_top", 0.2);
  upside_down["y_bottom"] = 0.6;
  expect_input_error(upside_down, "dummy.y_top", "must be above y_bottom");
  expect_input_error(with("builtin", "sphere"), "dummy.mesh", "conflicts with dummy.builtin");
}

// tinyobjloader does not skip a UTF-8 byte order mark: it would hide the first vertex, and every
// face then point at the next one.
TEST_F(MeshSections, AByteOrderMarkChangesNothing) {
  const std::string box = prism_obj(regular_polygon(6, 0.2, {0.0, 0.0}), 0.0,
                                    regular_polygon(6, 0.2, {0.0, 0.0}), 1.0, true);
  const std::string first_vertex_first = box.substr(box.find('\n') + 1);  // no comment line
  write("plain.obj", first_vertex_first);
  write("bom.obj", "\xEF\xBB\xBF" + first_vertex_first);
  const DummySections plain = sections_of({{"mesh", "plain.obj"}});
  const DummySections bom = sections_of({{"mesh", "bom.obj"}});
  EXPECT_EQ(plain.y, bom.y);
  EXPECT_EQ(plain.cx, bom.cx);
  EXPECT_EQ(plain.cz, bom.cz);
  EXPECT_EQ(plain.radius, bom.radius);
}

}  // namespace
}  // namespace drape
