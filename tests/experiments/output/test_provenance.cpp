// Provenance: the build and machine fields, in summary.json and `drapelab --version`.
#include "experiments/output/provenance.hpp"

#include <gtest/gtest.h>

#include <regex>

#include "tests/support/drapelab_process.hpp"

namespace {

TEST(Provenance, BuildFieldsAreFilled) {
  const auto b = drape::build_provenance();
  EXPECT_TRUE(std::regex_match(b["version"].get<std::string>(), std::regex(R"(\d+\.\d+\.\d+)")));
  // A 40-digit commit, maybe -dirty, or unknown when built outside git.
  EXPECT_TRUE(std::regex_match(b["git_commit"].get<std::string>(),
                               std::regex("([0-9a-f]{40}(-dirty)?)|unknown")))
      << b["git_commit"];
  EXPECT_FALSE(b["build_type"].get<std::string>().empty());
  EXPECT_TRUE(std::regex_match(b["sundials_version"].get<std::string>(),
                               std::regex(R"(\d+\.\d+\.\d+.*)")));
}

TEST(Provenance, RunFieldsAreDateAndMachine) {
  const auto p = drape::run_provenance();
  EXPECT_TRUE(std::regex_match(p["date"].get<std::string>(),
                               std::regex(R"(\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ)")));
  EXPECT_FALSE(p["machine"]["hostname"].get<std::string>().empty());
  EXPECT_FALSE(p["machine"]["cpu"].get<std::string>().empty());
  EXPECT_GE(p["machine"]["cores"].get<int>(), 1);
}

TEST(Provenance, VersionFlagPrintsEveryField) {
  const auto r = drape::testing::run_drapelab("--version");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const auto b = drape::build_provenance();
  EXPECT_EQ(r.out.rfind("drapelab " + b["version"].get<std::string>() + "\n", 0), 0u) << r.out;
  for (const char* key : {"git_commit", "build_type", "sundials_version"})
    EXPECT_NE(r.out.find(std::string(key) + ": " + b[key].get<std::string>() + "\n"),
              std::string::npos)
        << key << "\n" << r.out;
  EXPECT_NE(r.out.find("date: "), std::string::npos);
  EXPECT_NE(r.out.find("machine: "), std::string::npos);
}

TEST(Provenance, SummaryJsonCarriesIt) {
  const std::string dir = ::testing::TempDir() + "/provenance_run";
  const std::string scene = ::testing::TempDir() + "/provenance_scene.json";
  std::ofstream(scene) << R"({"cloth": {"rows": 3, "cols": 3, "spacing": 0.02,
    "origin": [0, 1.4, 0], "particle_mass": 0.001, "k_structural": 20}, "pins": [[0, 0]],
    "dummy": null, "integrator": {"name": "leapfrog", "dt": 0.001}, "duration": 0.01})";
  const auto r = drape::testing::run_drapelab("run " + scene + " --out " + dir + " --quiet --overwrite");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto summary = nlohmann::json::parse(drape::testing::read_text(dir + "/summary.json"));
  const auto b = drape::build_provenance();
  for (const char* key : {"version", "git_commit", "build_type", "sundials_version"})
    EXPECT_EQ(summary[key], b[key]) << key;
  EXPECT_TRUE(summary["date"].is_string());
  EXPECT_TRUE(summary["machine"]["cpu"].is_string());
  EXPECT_TRUE(summary["machine"]["cores"].is_number_integer());
}

}  // namespace
