// trace.csv and VTK frames: written at interval crossings and events, never changing the run.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/scene/scene.hpp"
#include "experiments/runner/run_scene.hpp"

namespace {

namespace fs = std::filesystem;

int count_lines(const fs::path& file) {
  std::ifstream in(file);
  int n = 0;
  for (std::string line; std::getline(in, line);) ++n;
  return n;
}

drape::Scene hanging(double trace_interval, double vtk_interval) {
  const auto source = nlohmann::json::parse(R"({
    "cloth": {"rows": 3, "cols": 4, "spacing": 0.02, "origin": [0, 1.4, 0],
              "particle_mass": 0.001, "k_structural": 20},
    "pins": [[0, 0]], "dummy": null,
    "integrator": {"name": "leapfrog", "dt": 0.001}, "duration": 0.1})");
  drape::Scene scene = drape::parse_scene(source, "test.json", ".");
  scene.output.trace_interval = trace_interval;
  scene.output.vtk_interval = vtk_interval;
  return scene;
}

TEST(FrameRecorder, WritesFramesAtIntervalsWithoutChangingTheRun) {
  const fs::path plain = fs::path(::testing::TempDir()) / "frames_plain";
  const fs::path traced = fs::path(::testing::TempDir()) / "frames_traced";
  fs::remove_all(plain);
  fs::remove_all(traced);
  const auto a = drape::run_scene(hanging(0.0, 0.0), plain);
  // 0.025 is no multiple of dt: frames land on the first step after each multiple.
  const auto b = drape::run_scene(hanging(0.025, 0.05), traced);
  EXPECT_FALSE(fs::exists(plain / "trace.csv"));
  EXPECT_FALSE(fs::exists(plain / "frames"));
  EXPECT_EQ(a.summary["steps"], b.summary["steps"]);
  EXPECT_EQ(a.summary["energy_final"], b.summary["energy_final"]);

  // t = 0, 0.025, 0.05, 0.075, 0.1: five frames of 12 particles and a header.
  EXPECT_EQ(count_lines(traced / "trace.csv"), 1 + 5 * 12);
  for (const char* frame : {"frame_00000.vtk", "frame_00001.vtk", "frame_00002.vtk"})
    EXPECT_TRUE(fs::exists(traced / "frames" / frame)) << frame;
  EXPECT_FALSE(fs::exists(traced / "frames" / "frame_00003.vtk"));

  std::ifstream vtk(traced / "frames" / "frame_00001.vtk");
  std::string text((std::istreambuf_iterator<char>(vtk)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text.rfind("# vtk DataFile Version 3.0\n", 0), 0u);
  EXPECT_NE(text.find("POINTS 12 double"), std::string::npos);
  EXPECT_NE(text.find("POLYGONS 6 30"), std::string::npos);  // (3-1) x (4-1) quads
  EXPECT_NE(text.find("TIME 1 1 double\n0.050000000000000003"), std::string::npos);
}

}  // namespace
