// A run folder never mixes two runs: --out checks, clearing, summary.json last (docs/outputs.md).
#include "experiments/output/run_folder.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>

#include "tests/support/test_support.hpp"

namespace drape {
namespace {

namespace fs = std::filesystem;

fs::path fresh(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("run_folder_" + name);
  fs::remove_all(dir);
  return dir;
}

std::string check(const fs::path& dir, bool overwrite) {
  return testing::input_error_message([&] { check_run_folder(dir, overwrite); });
}

TEST(RunFolder, NewAndEmptyFoldersAreAccepted) {
  const fs::path dir = fresh("new");
  EXPECT_EQ(check(dir / "a" / "b", false), "no error");
  fs::create_directories(dir);
  std::ofstream(dir / "notes.txt") << "mine";  // not a run file
  EXPECT_EQ(check(dir, false), "no error");
  EXPECT_FALSE(fs::exists(dir / "a")) << "checking creates nothing";
}

TEST(RunFolder, AnotherRunsFilesNeedOverwrite) {
  const fs::path dir = fresh("stale");
  fs::create_directories(dir / "frames");
  std::ofstream(dir / "summary.json") << "{}";
  std::ofstream(dir / "state.csv") << "old";
  EXPECT_EQ(check(dir, false),
            dir.string() + ": --out: holds another run's files (summary.json, state.csv, frames); "
                           "pass --overwrite to replace them, or choose another folder");
  EXPECT_EQ(check(dir, true), "no error");
}

// A run's files beside an experiment's would make the experiment refuse to resume.
TEST(RunFolder, AnExperimentsFolderIsRefused) {
  const fs::path dir = fresh("experiment");
  fs::create_directories(dir);
  std::ofstream(dir / "experiment.json") << "{}";
  EXPECT_EQ(testing::input_error_message([&] { check_run_folder_not_experiment(dir); }),
            dir.string() + ": --out: holds an experiment (experiment.json): choose another folder");
  EXPECT_EQ(check(dir, false), "no error");  // an experiment checks its own folder so
}

TEST(RunFolder, AFileOrAnUnwritablePlaceIsRefused) {
  const fs::path dir = fresh("file");
  fs::create_directories(dir);
  std::ofstream(dir / "taken") << "x";
  EXPECT_EQ(check(dir / "taken", true), (dir / "taken").string() + ": --out: exists and is not a folder");
  EXPECT_EQ(check(dir / "taken" / "sub", true),
            (dir / "taken" / "sub").string() + ": --out: cannot be created: " +
                (dir / "taken").string() + " is not a folder");
  if (::geteuid() != 0) {  // root writes anywhere
    fs::create_directories(dir / "locked");
    fs::permissions(dir / "locked", fs::perms::owner_read | fs::perms::owner_exec);
    EXPECT_EQ(check(dir / "locked" / "out", false),
              (dir / "locked" / "out").string() + ": --out: cannot be created: " +
                  (dir / "locked").string() + " is not writable");
    fs::permissions(dir / "locked", fs::perms::owner_all);
  }
  EXPECT_EQ(check("/proc/drapelab_out", false).rfind("/proc/drapelab_out: --out: cannot be created", 0),
            0u);
  // `--out ""`: a folder of no name was "<input>: --out: cannot be created:  is not a folder".
  EXPECT_EQ(check("", true), "--out: is empty: name the output folder");
}

// --overwrite removes all or nothing: a frames/ folder it cannot empty must be found before
// summary.json and the CSV files are gone.
TEST(RunFolder, OverwriteThatCannotRemoveEverythingIsRefusedFirst) {
  if (::geteuid() == 0) GTEST_SKIP() << "root removes anything (checked as nobody by hand)";
  const fs::path dir = fresh("locked_frames");
  fs::create_directories(dir / "frames");
  std::ofstream(dir / "summary.json") << "{}";
  std::ofstream(dir / "frames" / "frame_00001.vtk") << "old";
  fs::permissions(dir / "frames", fs::perms::owner_read | fs::perms::owner_exec);
  EXPECT_EQ(check(dir, true),
            dir.string() + ": --out: cannot replace its files: " +
                (dir / "frames" / "frame_00001.vtk").string() +
                " cannot be removed (its folder is not writable or cannot be read); nothing was "
                "removed");
  fs::permissions(dir / "frames", fs::perms::owner_all);
  EXPECT_EQ(check(dir, true), "no error");
  EXPECT_TRUE(fs::exists(dir / "summary.json")) << "checking removes nothing";
}

TEST(RunFolder, ClearingRemovesOnlyRunFiles) {
  const fs::path dir = fresh("clear");
  fs::create_directories(dir / "frames");
  for (const char* name : {"summary.json", "energy.csv", "state.csv", "notes.txt", "run.json"})
    std::ofstream(dir / name) << "old";
  clear_run_folder(dir);
  EXPECT_TRUE(run_files_in(dir).empty());
  EXPECT_TRUE(fs::exists(dir / "notes.txt"));
  EXPECT_TRUE(fs::exists(dir / "run.json")) << "the experiment runner's own file stays";
}

}  // namespace
}  // namespace drape
