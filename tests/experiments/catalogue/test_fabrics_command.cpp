// `drapelab fabrics` and `cloth.fabric` end to end (docs/fabrics.md): the JSON list, the exit
// status of an unknown fabric, and the derived values written back into summary.json.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

namespace {

namespace fs = std::filesystem;

// Runs drapelab with `args`; returns its exit status and stdout (stderr into `err_file`).
int drapelab(const std::string& args, std::string& out, const fs::path& err_file) {
  const std::string cmd = std::string(DRAPELAB_EXE) + " " + args + " 2> " + err_file.string();
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) return -1;
  char buffer[4096];
  out.clear();
  while (const std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) out.append(buffer, n);
  const int status = pclose(pipe);
  return WEXITSTATUS(status);
}

std::string read_text(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

fs::path temp(const std::string& name) {
  return fs::path(::testing::TempDir()) / ("fabrics_command_" + name);
}

nlohmann::json knit_scene() {
  return nlohmann::json::parse(R"({
    "cloth": {"rows": 4, "cols": 4, "spacing": 0.02, "origin": [0, 1.4, 0.2],
              "fabric": "ivory-rib-knit", "damping_spring": 0.01},
    "pins": [[0, 0], [0, 3]],
    "dummy": null,
    "integrator": {"name": "leapfrog", "dt": 0.0002},
    "duration": 0.01
  })");
}

TEST(FabricsCommand, JsonListsEveryPresetWithSourceAndProperties) {
  std::string out;
  ASSERT_EQ(drapelab("fabrics --json", out, temp("json_err.txt")), 0);
  const auto list = nlohmann::json::parse(out);
  ASSERT_TRUE(list.is_array());
  ASSERT_GE(list.size(), 3u);
  bool paper = false;
  for (const auto& f : list) {
    for (const char* key : {"name", "source", "areal_density", "tensile_stiffness",
                            "shear_stiffness", "bending_rigidity"})
      EXPECT_TRUE(f.contains(key)) << key << " in " << f.dump();
    paper = paper || f["name"] == "paper";
  }
  EXPECT_TRUE(paper);
}

TEST(FabricsCommand, UnknownFabricExitsWithTwoNamingTheField) {
  nlohmann::json scene = knit_scene();
  scene["cloth"]["fabric"] = "velvet";
  const fs::path file = temp("unknown.json");
  std::ofstream(file) << scene.dump();
  std::string out;
  const fs::path err = temp("unknown_err.txt");
  EXPECT_EQ(drapelab("run " + file.string() + " --out " + temp("unknown_out").string(), out, err), 2);
  EXPECT_NE(read_text(err).find("cloth.fabric: unknown fabric 'velvet'"), std::string::npos)
      << read_text(err);
}

TEST(FabricsCommand, SummaryHoldsTheDerivedValues) {
  const fs::path file = temp("knit.json"), dir = temp("knit_out");
  std::ofstream(file) << knit_scene().dump();
  std::string out;
  ASSERT_EQ(drapelab("run " + file.string() + " --quiet --overwrite --out " + dir.string(), out,
                     temp("knit_err.txt")), 0);
  const auto summary = nlohmann::json::parse(read_text(dir / "summary.json"));
  const auto& cloth = summary["scene"]["cloth"];
  EXPECT_EQ(cloth["fabric"], "ivory-rib-knit");
  EXPECT_NEAR(cloth["particle_mass"].get<double>(), 0.276 * 4e-4, 1e-15);
  EXPECT_NEAR(cloth["k_shear"].get<double>(), 83.175644 / 2, 1e-9);
}

}  // namespace
