// The files a run writes (docs/model.md section 9): state.csv read back to the last bit, JSON
// written under a temporary name then renamed, a failed write an OutputError naming the file.
#include "experiments/output/run_files.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "experiments/viewer/csv_table.hpp"
#include "tests/support/test_support.hpp"

namespace drape {
namespace {

namespace fs = std::filesystem;

fs::path fresh(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("run_files_" + name);
  fs::remove_all(dir);
  return dir;
}

TEST(RunFiles, StateCsvHoldsEveryParticleWithRoundTripPrecision) {
  const fs::path dir = fresh("state");
  fs::create_directories(dir);
  ClothSystem s(build_cloth(testing::small_cloth(2, 3)), nullptr, ForceParams{});
  s.constraints().fix_at(2, s.cloth().rest_positions.segment<3>(6));
  const Eigen::VectorXd y = testing::jitter(s.initial_state(0.0), 0.1, 5);
  write_state_csv(dir / "state.csv", s, y);
  std::ifstream in(dir / "state.csv");
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header, "index,row,col,x,y,z,vx,vy,vz,fixed");
  const CsvTable table(dir / "state.csv", {"index", "row", "col", "x", "y", "z", "vx", "vy", "vz", "fixed"});
  ASSERT_EQ(table.rows(), 6);
  for (int i = 0; i < 6; ++i) {
    EXPECT_EQ(table.at(i, 0), i);
    EXPECT_EQ(table.at(i, 1), i / 3) << "row of a 2 x 3 grid";
    EXPECT_EQ(table.at(i, 2), i % 3);
    for (int a = 0; a < 3; ++a) {
      EXPECT_EQ(table.at(i, 3 + a), y[3 * i + a]) << "%.17g reads back the same double";
      EXPECT_EQ(table.at(i, 6 + a), y[18 + 3 * i + a]);
    }
    EXPECT_EQ(table.at(i, 9), i == 2 ? 1.0 : 0.0);
  }
}

TEST(RunFiles, AFailedWriteIsAnOutputErrorNamingTheFile) {
  std::ofstream failed;
  failed.setstate(std::ios::badbit);
  errno = ENOSPC;
  try {
    check_written(failed, "out/energy.csv");
    FAIL() << "no error";
  } catch (const OutputError& e) {
    EXPECT_STREQ(e.what(), "cannot write out/energy.csv: No space left on device");
  }
  const fs::path missing = fresh("missing") / "state.csv";
  try {
    open_for_writing(missing);
    FAIL() << "no error";
  } catch (const OutputError& e) {
    EXPECT_EQ(std::string(e.what()), "cannot write " + missing.string() + ": No such file or directory");
  }
}

TEST(RunFiles, AtomicWriteKeepsTheOldFileWhenTheWriterThrows) {
  const fs::path dir = fresh("atomic_throw");
  fs::create_directories(dir);
  std::ofstream(dir / "result.json") << "old";
  EXPECT_THROW(write_file_atomic(dir / "result.json", ".part",
                                 [](std::ostream& out) {
                                   out << "half";
                                   throw std::runtime_error("killed");
                                 }),
               std::runtime_error);
  std::ifstream in(dir / "result.json");
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), "old");
  EXPECT_TRUE(fs::exists(dir / "result.json.part")) << "at most the temporary is left";
}

TEST(RunFolder, JsonIsWrittenUnderATemporaryNameThenRenamed) {
  const fs::path dir = fresh("json_atomic");
  fs::create_directories(dir);
  std::ofstream(dir / "summary.json") << "{\"status\": \"old\"}";
  write_json(dir / "summary.json", {{"status", "ok"}});
  EXPECT_FALSE(fs::exists(dir / "summary.json.tmp"));
  std::ifstream in(dir / "summary.json");
  EXPECT_EQ(nlohmann::json::parse(in)["status"], "ok");
}

TEST(RunFolder, JsonWithBytesThatAreNotUtf8IsWrittenWithReplacementCharacters) {
  // A path from the command line may hold any bytes but 0 and '/'.
  const fs::path dir = fresh("json_not_utf8");
  fs::create_directories(dir);
  write_json(dir / "summary.json", {{"scene", "e\xff/s.json"}});
  std::ifstream in(dir / "summary.json");
  EXPECT_EQ(nlohmann::json::parse(in)["scene"], "e\xef\xbf\xbd/s.json");  // U+FFFD
}

}  // namespace
}  // namespace drape
