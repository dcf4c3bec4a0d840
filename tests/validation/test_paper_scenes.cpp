// The shipped scenes of the paper's figures and Table 1 run to the end with their events in
// order, and the same input gives the same state.csv byte for byte.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/scene/scene.hpp"
#include "experiments/runner/run_scene.hpp"

namespace drape {
namespace {

namespace fs = std::filesystem;

const fs::path scenes = fs::path(DRAPE_SOURCE_DIR) / "experiments" / "scenes";

RunOutcome run(const std::string& name, const fs::path& out) {
  fs::remove_all(out);
  return run_scene(load_scene((scenes / name).string()), out);
}

std::vector<std::string> event_types(const RunOutcome& outcome) {
  std::vector<std::string> types;
  for (const auto& e : outcome.summary["events"]) types.push_back(e["type"].get<std::string>());
  return types;
}

std::string read_text(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

struct SceneCase {
  const char* file;
  std::vector<std::string> events;
};

class PaperScene : public ::testing::TestWithParam<SceneCase> {};

TEST_P(PaperScene, RunsToTheEndWithItsEventsInOrder) {
  const SceneCase& c = GetParam();
  const fs::path out = fs::path(::testing::TempDir()) / "paper" / c.file;
  const RunOutcome outcome = run(c.file, out);
  EXPECT_EQ(outcome.status, "ok") << outcome.reason;
  EXPECT_EQ(event_types(outcome), c.events) << outcome.summary["events"].dump(1);
  EXPECT_DOUBLE_EQ(outcome.summary["sim_time"].get<double>(),
                   outcome.summary["duration"].get<double>());
}

INSTANTIATE_TEST_SUITE_P(
    Figures, PaperScene,
    ::testing::Values(
        SceneCase{"fig2_hold.json", {"hold"}}, SceneCase{"fig3_release.json", {"release"}},
        SceneCase{"fig4_attach.json", {"hold", "attach", "attach_fixed"}},
        SceneCase{"fig6_map.json", {"map"}},
        SceneCase{"combination1_hold_release.json", {"hold", "release"}},
        SceneCase{"combination2_release_hold.json", {"release", "hold"}},
        SceneCase{"combination3_hold_attach_release.json",
                  {"hold", "attach", "attach_fixed", "release"}},
        SceneCase{"combination4_hold_release_attach.json",
                  {"hold", "release", "attach", "attach_fixed"}},
        SceneCase{"kinect_drawlines_hold.json", {"hold", "release"}}),
    [](const auto& test) {
      std::string name = fs::path(test.param.file).stem().string();
      for (char& ch : name)
        if (ch == '_') ch = 'X';
      return name;
    });

TEST(PaperScenes, SameInputGivesByteIdenticalState) {
  const fs::path a = fs::path(::testing::TempDir()) / "replay_a";
  const fs::path b = fs::path(::testing::TempDir()) / "replay_b";
  ASSERT_EQ(run("combination4_hold_release_attach.json", a).status, "ok");
  ASSERT_EQ(run("combination4_hold_release_attach.json", b).status, "ok");
  const std::string state = read_text(a / "state.csv");
  EXPECT_GT(state.size(), 10000u);
  EXPECT_EQ(state, read_text(b / "state.csv"));
}

TEST(PaperScenes, AttachedParticleEndsFixedWhereTheSummarySays) {
  const fs::path out = fs::path(::testing::TempDir()) / "attach_state";
  const RunOutcome outcome = run("fig4_attach.json", out);
  const auto& fixed = outcome.summary["events"][2];
  ASSERT_EQ(fixed["type"], "attach_fixed");
  const int particle = fixed["particle"];
  std::istringstream state(read_text(out / "state.csv"));
  std::string line;
  while (std::getline(state, line))
    if (line.rfind(std::to_string(particle) + ",", 0) == 0) break;
  EXPECT_EQ(line.back(), '1') << "the attached particle is fixed at the end: " << line;
}

}  // namespace
}  // namespace drape
