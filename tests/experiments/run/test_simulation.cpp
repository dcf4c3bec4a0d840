// The shared step/event loop: outputs never change the steps, events land exactly and reset the
// integrator, summary.json reports the steps taken, and the interpolant samples between steps.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "core/scene/scene.hpp"
#include "experiments/runner/run_scene.hpp"
#include "experiments/run/scene_simulation.hpp"

namespace drape {
namespace {

namespace fs = std::filesystem;

std::string read_text(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// A 4 x 5 cloth pinned at one corner, swinging under gravity, with the given method and output.
Scene swinging(const std::string& integrator, double energy_interval, double trace_interval = 0.0) {
  auto source = nlohmann::json::parse(R"({
    "cloth": {"rows": 4, "cols": 5, "spacing": 0.02, "origin": [0, 1.4, 0],
              "row_dir": [0, 0, 1], "particle_mass": 0.001, "k_structural": 20,
              "k_shear": 5, "damping_spring": 0.001},
    "pins": [[0, 0]], "dummy": null, "duration": 0.5})");
  source["integrator"] = nlohmann::json::parse(integrator);
  source["output"] = {{"energy_interval", energy_interval}, {"trace_interval", trace_interval}};
  return parse_scene(source, "test.json", ".");
}

RunOutcome run_into(const Scene& scene, const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("simulation_" + name);
  fs::remove_all(dir);
  return run_scene(scene, dir);
}

std::string state_of(const std::string& name) {
  return read_text(fs::path(::testing::TempDir()) / ("simulation_" + name) / "state.csv");
}

TEST(Simulation, OutputIntervalsLeaveTheStepsAndTheFinalStateUnchanged) {
  for (const std::string method :
       {R"({"name": "leapfrog", "dt": 0.001})", R"({"name": "implicit-euler", "dt": 0.0333333})"}) {
    // An energy interval finer than dt (3e-4), none (every step), coarser (0.05), and a trace.
    const RunOutcome fine = run_into(swinging(method, 3e-4), "fine");
    const RunOutcome every = run_into(swinging(method, 0.0), "every");
    const RunOutcome coarse = run_into(swinging(method, 0.05, 0.001), "coarse");
    ASSERT_EQ(fine.status, "ok") << method;
    const double dt = nlohmann::json::parse(method)["dt"];
    const long expected = static_cast<long>(std::ceil(0.5 / dt - 1e-9));
    for (const RunOutcome* run : {&fine, &every, &coarse}) {
      EXPECT_EQ(run->summary["steps"], expected) << method;
      EXPECT_EQ(run->summary["dt"], dt);
      EXPECT_NEAR(run->summary["step_max"].get<double>(), dt, 1e-12 * dt) << method;
    }
    // Bit for bit: the same steps give the same state.
    EXPECT_EQ(state_of("fine"), state_of("every")) << method;
    EXPECT_EQ(state_of("fine"), state_of("coarse")) << method;
  }
}

TEST(Simulation, ReportsTheStepsTakenBesideTheStepAskedFor) {
  const RunOutcome run =
      run_into(swinging(R"({"name": "implicit-euler", "dt": 0.04})", 0.01), "reported");
  // 0.5 s in steps of 0.04 s: twelve full steps and one of 0.02 s to land on the end.
  EXPECT_EQ(run.summary["steps"], 13);
  EXPECT_NEAR(run.summary["step_max"].get<double>(), 0.04, 1e-14);
  EXPECT_NEAR(run.summary["step_min"].get<double>(), 0.02, 1e-12);
  EXPECT_NEAR(run.summary["step_mean"].get<double>(), 0.5 / 13, 1e-12);
}

// Records the time of every step end and whether an event changed the state there.
struct StepLog : SimulationObserver {
  std::vector<double> times;
  std::vector<double> event_times;
  void on_start(const Simulation&) override {}
  void on_step(const Simulation& s, bool event) override {
    times.push_back(s.time());
    if (event) event_times.push_back(s.time());
  }
};

TEST(Simulation, LandsExactlyOnKeyTimesAndResetsTheIntegratorThere) {
  // Inline hand input whose 'm' key (map) comes at 0.0123 s, no multiple of dt = 1 ms.
  const auto source = nlohmann::json::parse(R"({
    "cloth": {"rows": 4, "cols": 4, "spacing": 0.02, "origin": [-0.03, 1.5, 0.2],
              "row_dir": [0, 0, -1], "particle_mass": 0.001, "k_structural": 20},
    "dummy": {"builtin": "cylinder", "radius": 0.12, "y_top": 1.4, "y_bottom": 0.6,
              "sections": 41, "points": 32},
    "input": {"events": [{"t": 0.0, "keys": []}, {"t": 0.0123, "keys": ["m"]},
                         {"t": 0.1, "keys": []}]},
    "integrator": {"name": "leapfrog", "dt": 0.001}, "duration": 0.05})");
  SceneSimulation run(parse_scene(source, "keys.json", "."));
  StepLog log;
  run.simulation().add_observer(log);
  ASSERT_EQ(run.simulation().run().status, "ok") << run.simulation().status().reason;
  ASSERT_EQ(log.event_times.size(), 1u);
  EXPECT_EQ(log.event_times[0], 0.0123) << "the step before the key is shortened to land on it";
  EXPECT_EQ(run.simulation().integrator().counters().resets, 1);
  // Steps before and after the key are the full dt.
  EXPECT_NEAR(log.times[0], 0.001, 1e-15);
  const auto key = std::find(log.times.begin(), log.times.end(), 0.0123);
  ASSERT_NE(key, log.times.end());
  EXPECT_NEAR(*(key + 1) - *key, 0.001, 1e-12);
  EXPECT_EQ(log.times.back(), 0.05);
}

TEST(Simulation, TraceFramesBetweenStepsComeFromTheInterpolantAtExactTimes) {
  // Two particles fall, their spring at rest: x(t) = x0 + g t^2 / 2 is quadratic, so the cubic Hermite
  // interpolant of the step ends reproduces it between steps of 10 ms at the 1 ms frames.
  const auto source = nlohmann::json::parse(R"({
    "cloth": {"rows": 1, "cols": 2, "spacing": 0.02, "origin": [0, 1, 0],
              "particle_mass": 0.001, "k_structural": 20},
    "dummy": null, "integrator": {"name": "leapfrog", "dt": 0.01}, "duration": 0.1,
    "output": {"trace_interval": 0.001}})");
  const RunOutcome run = run_into(parse_scene(source, "fall.json", "."), "fall");
  ASSERT_EQ(run.summary["steps"], 10);
  std::istringstream trace(read_text(fs::path(::testing::TempDir()) / "simulation_fall" / "trace.csv"));
  std::string line;
  std::getline(trace, line);
  int frames = 0;
  for (; std::getline(trace, line); ++frames) {
    double t, x, y, z, vx, vy, vz;
    char c;
    int index;
    std::istringstream row(line);
    row >> t >> c >> index >> c >> x >> c >> y >> c >> z >> c >> vx >> c >> vy >> c >> vz;
    EXPECT_NEAR(t, (frames / 2) * 0.001, 1e-12);
    EXPECT_NEAR(y, 1.0 - 0.5 * 9.81 * t * t, 1e-12) << t;
    EXPECT_NEAR(vy, -9.81 * t, 1e-11) << t;
  }
  EXPECT_EQ(frames, 2 * 101);
}

// Spends `per_step` seconds of process CPU time (std::clock) in every on_step, as a writer or a
// restart branch would, and adds up what it spent.
struct CpuBurner : SimulationObserver {
  explicit CpuBurner(double per_step) : per_step(per_step) {}
  double per_step;
  double spent = 0.0;
  void on_start(const Simulation&) override {}
  void on_step(const Simulation&, bool) override {
    const std::clock_t start = std::clock();
    while (std::clock() - start < per_step * CLOCKS_PER_SEC) {
    }
    spent += static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
  }
};

// cpu_seconds() is the process's CPU time over the loop less the observers' (docs/outputs.md):
// measured around run() with std::clock, the loop's CPU time is cpu_seconds() plus what the
// observer spent, up to the clock calls. Counted in, the observer's time alone would make
// cpu_seconds() at least burner.spent; the stepping of a 4 x 5 cloth (19 ms under the address
// sanitizer) is far below half of it.
TEST(Simulation, CpuTimeLeavesTheObserversOut) {
  SceneSimulation run(swinging(R"({"name": "implicit-euler", "dt": 0.01})", 0.0));
  CpuBurner burner(0.01);
  run.simulation().add_observer(burner);
  const std::clock_t start = std::clock();
  ASSERT_EQ(run.simulation().run().status, "ok");
  const double around = static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
  ASSERT_GT(burner.spent, 50 * 0.01 * 0.99) << "50 steps of 10 ms";
  EXPECT_GT(run.simulation().cpu_seconds(), 0.0);
  EXPECT_LT(run.simulation().cpu_seconds(), 0.5 * burner.spent);
  EXPECT_NEAR(run.simulation().cpu_seconds() + burner.spent, around, 0.01 * around);
}

// The runaway bound allows a free fall over `runaway_horizon` (default: the duration), so a run
// cut short with the longer run's horizon, as a live run's replay is, diverges where the longer
// run did, with its reason; cut short without it, its bound is the shorter fall's.
TEST(Simulation, ARunCutShortKeepsTheRunawayBoundOfItsHorizon) {
  const auto unstable = [](double duration, double horizon) {
    Scene scene = swinging(R"({"name": "leapfrog", "dt": 0.008})", 0.05);
    scene.duration = duration;
    scene.runaway_horizon = horizon;
    return scene;
  };
  // The bound the reason prints: the cloth starts at rest and unstretched, so 10 + 2 |g| horizon.
  const auto bound_text = [](double horizon) {
    return fmt::format("above the bound {:.3g} m/s", 10.0 + 2.0 * 9.81 * horizon);
  };
  const RunOutcome whole = run_into(unstable(0.5, 0.5), "horizon_whole");
  ASSERT_EQ(whole.status, "diverged");
  EXPECT_NE(whole.reason.find(bound_text(0.5)), std::string::npos) << whole.reason;
  const double t = whole.summary["sim_time"];
  ASSERT_LT(t, 0.25);
  const RunOutcome cut = run_into(unstable(t, 0.5), "horizon_cut");
  EXPECT_EQ(cut.status, "diverged");
  EXPECT_EQ(cut.summary["sim_time"], whole.summary["sim_time"]);
  EXPECT_EQ(cut.reason, whole.reason);
  const RunOutcome shrunk = run_into(unstable(t, t), "horizon_shrunk");
  EXPECT_EQ(shrunk.status, "diverged");
  EXPECT_NE(shrunk.reason.find(bound_text(t)), std::string::npos) << shrunk.reason;
}

// An undriven cloth can only lose energy; a run that gains more than 1e-3 of E(0) says so in
// summary.json's warnings (and drapelab run prints them). The gaining case is the paper's
// penetration correction throwing a particle off a coarse sphere's pole (docs/known_issues.md:
// energy_rise_max_rel 22.6); the stable swinging cloth's bounded error stays far below.
TEST(Simulation, AnUndrivenRunThatGainsEnergyIsFlagged) {
  const RunOutcome stable = run_into(swinging(R"({"name": "leapfrog", "dt": 0.0005})", 0.01), "stable");
  ASSERT_EQ(stable.status, "ok");
  EXPECT_LT(stable.summary["energy_rise_max_rel"].get<double>(), 1e-4);
  EXPECT_EQ(stable.summary["warnings"], nlohmann::json::array());
  const RunOutcome pumped = run_into(parse_scene(nlohmann::json::parse(R"({
    "cloth": {"rows": 2, "cols": 1, "spacing": 0.25, "origin": [0, 0.9, 0], "particle_mass": 0.001,
              "k_structural": 1e-9, "damping_air": 0.0},
    "pins": [[0, 0]],
    "dummy": {"builtin": "sphere", "radius": 0.1, "center": [0, 0.5, 0], "sections": 20, "points": 16},
    "collision": {"threshold": 0.01, "stiffness": 10, "model": "particle"},
    "integrator": {"name": "leapfrog", "dt": 1e-4}, "duration": 3.0,
    "output": {"energy_interval": 0.01}})"), "pump.json", "."), "pumped");
  ASSERT_EQ(pumped.status, "ok");
  const double rise = pumped.summary["energy_rise_max_rel"];
  EXPECT_GT(rise, 1.0);
  ASSERT_EQ(pumped.summary["warnings"].size(), 1u);
  EXPECT_EQ(pumped.summary["warnings"][0].get<std::string>().rfind(
                fmt::format("the energy rose above its start by {:.3g} |E(0)|", rise), 0), 0u)
      << pumped.summary["warnings"][0];
}

}  // namespace
}  // namespace drape
