// The output folder of an experiment: what --out refuses, what it resumes, and what --overwrite
// clears (docs/experiments.md, What it writes).
#include "experiments/sweep/experiment_folder.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <initializer_list>

#include "tests/experiments/sweep/experiment_fixtures.hpp"
#include "tests/support/test_support.hpp"

namespace {

using namespace drape::experiment_fixtures;
using drape::testing::input_error_message;

/// The names in `dir`, sorted.
std::vector<std::string> names_in(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename());
  std::sort(names.begin(), names.end());
  return names;
}

std::string refusal(const fs::path& dir, bool overwrite = false) {
  return input_error_message([&] { drape::check_experiment_folder(dir, "small", overwrite); });
}

TEST(ExperimentFolder, AFileOrAFolderThatCannotBeCreatedIsRefused) {
  const fs::path dir = temp_dir("folder_file");
  std::ofstream(dir / "a_file") << "x";
  EXPECT_EQ(refusal(dir / "a_file"), (dir / "a_file").string() + ": --out: exists and is not a folder");
  EXPECT_EQ(refusal(dir / "a_file" / "x"), (dir / "a_file" / "x").string() +
                                               ": --out: cannot be created: " +
                                               (dir / "a_file").string() + " is not a folder");
  EXPECT_EQ(refusal(dir / "new" / "deeper"), "no error");
  // A file where the experiment writes its runs folder is refused, unless --overwrite clears it.
  fs::create_directories(dir / "with_file");
  std::ofstream(dir / "with_file" / "runs") << "x";
  EXPECT_EQ(refusal(dir / "with_file"), (dir / "with_file").string() +
                                            ": --out: holds a file 'runs' where the experiment "
                                            "writes a folder; remove it, choose another folder "
                                            "or pass --overwrite");
  EXPECT_EQ(refusal(dir / "with_file", true), "no error");
  EXPECT_FALSE(fs::exists(dir / "new")) << "the check changes nothing";
}

TEST(ExperimentFolder, ARunsOrAnotherExperimentsFolderIsRefusedWithoutOverwrite) {
  const fs::path dir = temp_dir("folder_other");
  std::ofstream(dir / "summary.json") << "{}";
  EXPECT_EQ(refusal(dir).find(dir.string() + ": --out: holds another run's files (summary.json)"),
            0u) << refusal(dir);
  EXPECT_EQ(refusal(dir, true), "no error");
  fs::remove(dir / "summary.json");
  std::ofstream(dir / "experiment.json") << R"({"name": "good", "plan": []})";
  EXPECT_EQ(refusal(dir), dir.string() +
                              ": --out: holds the files of another experiment (experiment.json "
                              "names 'good', not 'small'); pass --overwrite to replace them, or "
                              "choose another folder");
  EXPECT_EQ(refusal(dir, true), "no error");
  // A damaged header is said to be one, not another experiment's named ''.
  std::ofstream(dir / "experiment.json") << R"({"name": "sma)";
  EXPECT_EQ(refusal(dir), dir.string() +
                              ": --out: holds an experiment.json that is not valid JSON "
                              "(damaged?); pass --overwrite to replace them, or choose another "
                              "folder");
  std::ofstream(dir / "experiment.json") << R"({"plan": []})";
  EXPECT_EQ(refusal(dir), dir.string() +
                              ": --out: holds an experiment.json without a name (not one drapelab "
                              "wrote); pass --overwrite to replace them, or choose another folder");
  // The same experiment resumes.
  std::ofstream(dir / "experiment.json") << R"({"name": "small", "plan": []})";
  EXPECT_EQ(refusal(dir), "no error");
}

/// A folder `name` with runs/a/, report/ and a file of each of `files`.
fs::path folder_with(const std::string& name, std::initializer_list<const char*> files) {
  const fs::path dir = temp_dir(name);
  fs::create_directories(dir / "runs" / "a");
  fs::create_directories(dir / "report");
  for (const char* file : files) std::ofstream(dir / file) << "x";
  return dir;
}

TEST(ExperimentFolder, OverwriteClearsOnlyRunAndExperimentFiles) {
  const fs::path dir = folder_with("folder_clear", {"experiment.json", "results.csv",
                                                    "results.json", "summary.json", "energy.csv",
                                                    "notes.txt"});
  drape::clear_experiment_folder(dir);
  EXPECT_EQ(names_in(dir), std::vector<std::string>{"notes.txt"});
}

// A new invocation removes the last one's table before it runs: stopped before it wrote its own,
// it left results.json of another plan, which the report read as the experiment's.
TEST(ExperimentFolder, ANewInvocationRemovesTheLastResultsTableOnly) {
  const fs::path dir = folder_with("folder_results", {"experiment.json", "results.csv",
                                                      "results.json", "summary.csv", "metrics.csv",
                                                      "notes.txt"});
  drape::remove_results_table(dir);
  EXPECT_EQ(names_in(dir), (std::vector<std::string>{"experiment.json", "metrics.csv", "notes.txt",
                                                     "report", "runs"}));
  drape::remove_results_table(dir);  // none there: nothing to do
}

}  // namespace
