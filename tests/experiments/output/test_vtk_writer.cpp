// The legacy VTK frames of frames/ (docs/outputs.md): read back token by token, the cloth's
// points, one quad per grid cell, velocities and flags, its time in a TIME field; the object's
// particles as vertices with outward unit normals.
#include "experiments/output/vtk_writer.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "core/dummy/dummy.hpp"
#include "tests/support/test_support.hpp"

namespace drape {
namespace {

namespace fs = std::filesystem;

fs::path fresh(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / "vtk_writer";
  fs::create_directories(dir);
  return dir / name;
}

/// The file's lines, and a stream positioned just after the line `section` starts.
struct VtkFile {
  std::string text;
  explicit VtkFile(const fs::path& file) {
    std::ifstream in(file);
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  std::istringstream after(const std::string& section) const {
    const std::size_t at = text.find("\n" + section);
    EXPECT_NE(at, std::string::npos) << section;
    return std::istringstream(text.substr(at + 1 + section.size()));
  }
};

TEST(VtkWriter, ClothFrameHoldsPointsCellsVelocitiesAndFlags) {
  ClothSystem s(build_cloth(testing::small_cloth(3, 4)), nullptr, ForceParams{});
  s.constraints().fix_at(0, s.cloth().rest_positions.head<3>());
  const Eigen::VectorXd y = testing::jitter(s.initial_state(0.0), 0.01, 11);
  ClothFrameData data;
  data.held.assign(12, 0);
  data.held[5] = 1;
  data.contact.assign(12, -1);
  data.contact[7] = 42;
  const fs::path file = fresh("frame_00003.vtk");
  const double t = 0.1 / 3.0;  // no short decimal: %.17g must carry every bit
  write_cloth_vtk(file, s, y, t, data);
  const VtkFile vtk(file);
  EXPECT_EQ(vtk.text.substr(0, vtk.text.find("FIELD")),
            fmt::format("# vtk DataFile Version 3.0\ndrapelab cloth t={:.17g}\nASCII\nDATASET POLYDATA\n", t));
  double time = 0.0;
  vtk.after("TIME 1 1 double") >> time;
  EXPECT_EQ(time, t);
  auto points = vtk.after("POINTS 12 double");
  for (int k = 0; k < 36; ++k) {
    double value = 0.0;
    points >> value;
    ASSERT_EQ(value, y[k]) << "coordinate " << k;
  }
  // (3 - 1) x (4 - 1) cells, each 4 indices round the square; cell (1, 2): 6, 7, 11, 10.
  auto polygons = vtk.after("POLYGONS 6 30");
  std::vector<int> cells(30);
  for (int& index : cells) polygons >> index;
  EXPECT_EQ(std::vector<int>(cells.begin() + 25, cells.end()), (std::vector<int>{4, 6, 7, 11, 10}));
  EXPECT_EQ(std::vector<int>(cells.begin(), cells.begin() + 5), (std::vector<int>{4, 0, 1, 5, 4}));
  auto velocities = vtk.after("POINT_DATA 12\nVECTORS velocity double");
  for (int k = 0; k < 36; ++k) {
    double value = 0.0;
    velocities >> value;
    ASSERT_EQ(value, y[36 + k]) << "velocity " << k;
  }
  const auto flags = [&](const std::string& section) {
    auto in = vtk.after(section);
    std::vector<int> values(12);
    for (int& v : values) in >> v;
    return values;
  };
  EXPECT_EQ(flags("SCALARS fixed int 1\nLOOKUP_TABLE default"),
            (std::vector<int>{1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}));
  EXPECT_EQ(flags("FIELD point_flags 2\nheld 1 12 int"), data.held);
  EXPECT_EQ(flags("contact 1 12 int"), data.contact);
}

TEST(VtkWriter, ObjectParticlesAreVerticesWithOutwardUnitNormals) {
  const Dummy sphere = make_dummy(
      nlohmann::json{{"builtin", "sphere"}, {"radius", 0.1}, {"center", {0.0, 1.0, 0.0}}}, "test",
      "dummy", ".");
  const fs::path file = fresh("dummy.vtk");
  write_dummy_vtk(file, sphere);
  const VtkFile vtk(file);
  const int n = sphere.size();
  ASSERT_GT(n, 10);
  auto points = vtk.after(fmt::format("POINTS {} double", n));
  std::vector<Vec3> p(static_cast<std::size_t>(n));
  for (Vec3& q : p) points >> q.x() >> q.y() >> q.z();
  auto vertices = vtk.after(fmt::format("VERTICES {} {}", n, 2 * n));
  for (int o = 0; o < n; ++o) {
    int one = 0, index = -1;
    vertices >> one >> index;
    ASSERT_EQ(one, 1);
    ASSERT_EQ(index, o);
  }
  auto normals = vtk.after(fmt::format("POINT_DATA {}\nNORMALS normal double", n));
  for (int o = 0; o < n; ++o) {
    Vec3 normal;
    normals >> normal.x() >> normal.y() >> normal.z();
    EXPECT_EQ(p[static_cast<std::size_t>(o)], sphere.position(o));
    EXPECT_NEAR(normal.norm(), 1.0, 1e-12);
    EXPECT_GT(normal.dot(p[static_cast<std::size_t>(o)] - Vec3(0.0, 1.0, 0.0)), 0.0) << "outward";
  }
}

}  // namespace
}  // namespace drape
