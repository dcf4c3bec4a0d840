// frames.vtk.series: complete JSON after every frame, each frame appended in place.
#include "experiments/output/vtk_series.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "experiments/output/run_files.hpp"

namespace {

namespace fs = std::filesystem;

nlohmann::json read_series(const fs::path& file) {
  std::ifstream in(file);
  return nlohmann::json::parse(in);
}

TEST(VtkSeries, IsCompleteAfterEveryFrame) {
  const fs::path dir = fs::path(::testing::TempDir()) / "vtk_series";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path file = dir / "frames.vtk.series";
  drape::VtkSeries series(file);
  EXPECT_FALSE(fs::exists(file));

  series.add("frame_00000.vtk", 0.0);
  EXPECT_EQ(read_series(file),
            nlohmann::json::parse(R"({"file-series-version": "1.0",
                                      "files": [{"name": "frame_00000.vtk", "time": 0.0}]})"));
  series.add("frame_00001.vtk", 0.1);
  series.add("frame_00002.vtk", 0.30000000000000004);
  const nlohmann::json three = read_series(file);
  EXPECT_EQ(three["file-series-version"], "1.0");
  ASSERT_EQ(three["files"].size(), 3u);
  EXPECT_EQ(three["files"][1]["name"], "frame_00001.vtk");
  EXPECT_EQ(three["files"][1]["time"].get<double>(), 0.1);
  EXPECT_EQ(three["files"][2]["name"], "frame_00002.vtk");
  // Round-trip precision: the time the frame's TIME field holds.
  EXPECT_EQ(three["files"][2]["time"].get<double>(), 0.30000000000000004);

  // A frame adds one line: the brackets are written again, never a second time behind.
  std::ifstream in(file);
  int lines = 0;
  for (std::string line; std::getline(in, line);) ++lines;
  EXPECT_EQ(lines, 1 + 3 + 1);
}

TEST(VtkSeries, UnwritableFileIsAnOutputError) {
  drape::VtkSeries series(fs::path(::testing::TempDir()) / "no_such_folder" / "frames.vtk.series");
  EXPECT_THROW(series.add("frame_00000.vtk", 0.0), drape::OutputError);
}

}  // namespace
