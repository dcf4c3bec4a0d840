// The restart error (docs/analysis.md, "Restart error"): the reference restarted from the
// run's state measures the run's convergence order, a reference that is the run's own method
// reproduces it exactly (state, fixed particles and manipulation progress all carried over),
// the run's own steps do not change, and bad input names restart_error's field.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/io/input_error.hpp"
#include "core/scene/scene.hpp"
#include "experiments/runner/run_scene.hpp"
#include "experiments/run/scene_simulation.hpp"

namespace drape {
namespace {

namespace fs = std::filesystem;

struct Row {
  double t, horizon, error_rms;
  std::string events, status;
};

std::vector<Row> read_rows(const fs::path& csv) {
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "t,events,horizon,status,error_rms,error_max,reference_motion_rms");
  std::vector<Row> rows;
  while (std::getline(in, line)) {
    std::stringstream fields(line);
    std::string t, events, horizon, status, rms;
    std::getline(fields, t, ',');
    std::getline(fields, events, ',');
    std::getline(fields, horizon, ',');
    std::getline(fields, status, ',');
    std::getline(fields, rms, ',');
    rows.push_back({std::stod(t), std::stod(horizon), std::stod(rms), events, status});
  }
  return rows;
}

// A 4 x 5 cloth pinned at one corner, swinging under gravity (no object).
nlohmann::json sheet(double damping_spring) {
  auto source = nlohmann::json::parse(R"({
    "cloth": {"rows": 4, "cols": 5, "spacing": 0.02, "origin": [0, 1.4, 0],
              "row_dir": [0, 0, 1], "particle_mass": 0.001, "k_structural": 20,
              "k_shear": 5, "damping_air": 0},
    "pins": [[0, 0]], "dummy": null, "duration": 0.2})");
  source["cloth"]["damping_spring"] = damping_spring;
  return source;
}

std::vector<Row> restart_rows(nlohmann::json source, const std::string& method,
                              const std::string& reference, const std::string& name,
                              const std::vector<double>& horizons = {0.05, 0.1}) {
  source["integrator"] = nlohmann::json::parse(method);
  source["restart_error"] = {{"reference", nlohmann::json::parse(reference)},
                             {"horizons", horizons}};
  const fs::path dir = fs::path(::testing::TempDir()) / ("restarts_" + name);
  fs::remove_all(dir);
  const RunOutcome outcome = run_scene(parse_scene(source, "test.json", "."), dir);
  EXPECT_EQ(outcome.summary["restart_error"]["rows_failed"], 0);
  return read_rows(dir / "restart_error.csv");
}

// Error after 0.1 s from the start, for leap-frog at dt and dt / 2: their ratio is 2^order.
double leapfrog_halving_ratio(double damping_spring) {
  const std::string reference = R"({"name": "leapfrog", "dt": 2e-6})";
  const auto coarse = restart_rows(sheet(damping_spring), R"({"name": "leapfrog", "dt": 4e-4})",
                                   reference, "coarse");
  const auto fine = restart_rows(sheet(damping_spring), R"({"name": "leapfrog", "dt": 2e-4})",
                                 reference, "fine");
  EXPECT_EQ(coarse.size(), 2u);
  EXPECT_EQ(coarse.back().events, "start");
  EXPECT_DOUBLE_EQ(coarse.back().horizon, 0.1);
  return coarse.back().error_rms / fine.back().error_rms;
}

TEST(ReferenceRestarts, LeapfrogIsSecondOrderWithoutDampingAndFirstOrderWithIt) {
  // Leap-frog evaluates velocity-dependent forces at the half-step velocity, so spring damping
  // costs it an order (docs/integrators/explicit.md): damping rate c / m = 50 / s here.
  EXPECT_NEAR(std::log2(leapfrog_halving_ratio(0.0)), 2.0, 0.1);
  EXPECT_NEAR(std::log2(leapfrog_halving_ratio(0.05)), 1.0, 0.15);
}

// The sheet with a hand that holds its far corner from the start and a release key at 0.1 s.
nlohmann::json held_sheet() {
  nlohmann::json source = sheet(0.001);
  const Scene plain = parse_scene(
      [&] {
        auto s = source;
        s["integrator"] = {{"name", "leapfrog"}, {"dt", 1e-3}};
        return s;
      }(),
      "test.json", ".");
  const SceneSimulation built(plain);
  const Vec3 corner = built.system().cloth().rest_positions.segment<3>(3 * 19);
  const auto hand = [&](double dx) {
    return nlohmann::json::array({corner.x() + dx, corner.y(), corner.z()});
  };
  source["input"] = {{"events",
                      {{{"t", 0.0}, {"right", hand(0.0)}},
                       {{"t", 0.1}, {"right", hand(0.03)}, {"keys", {"r"}}},
                       {{"t", 0.2}, {"right", hand(0.03)}}}}};
  source["manipulation"] = {{"hold_threshold", 0.01}, {"release", "held"}};
  return source;
}

TEST(ReferenceRestarts, TheRunsOwnMethodAsReferenceReproducesItExactlyAfterEveryEvent) {
  const std::string method = R"({"name": "leapfrog", "dt": 1e-3})";
  // Horizons shorter than the time between the events: at the release the reference's own
  // simulation is still at 0.05 s, holding, so only what the branch copies makes it match.
  const auto rows = restart_rows(held_sheet(), method, method, "itself", {0.02, 0.05});
  // The start (with the hold at t = 0 already applied) and the release, two horizons each.
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(rows[0].events, "start");
  EXPECT_EQ(rows[2].events, "release");
  EXPECT_NEAR(rows[2].t, 0.1, 1e-9);
  for (const Row& row : rows) {
    EXPECT_EQ(row.status, "ok");
    EXPECT_EQ(row.error_rms, 0.0) << row.t << " " << row.horizon;
  }
  // A different method from the same states has an error that the branch really measures.
  const auto other = restart_rows(held_sheet(), R"({"name": "symplectic-euler", "dt": 1e-3})",
                                  method, "other", {0.02, 0.05});
  ASSERT_EQ(other.size(), 4u);
  for (const Row& row : other) EXPECT_GT(row.error_rms, 1e-7);
}

TEST(ReferenceRestarts, TheRunsOwnStepsAndStateDoNotChange) {
  auto source = held_sheet();
  source["integrator"] = {{"name", "symplectic-euler"}, {"dt", 1e-3}};
  const fs::path plain_dir = fs::path(::testing::TempDir()) / "restarts_plain";
  const fs::path measured_dir = fs::path(::testing::TempDir()) / "restarts_measured";
  const RunOutcome plain = run_scene(parse_scene(source, "test.json", "."), plain_dir);
  source["restart_error"] = {{"reference", {{"name", "leapfrog"}, {"dt", 1e-4}}},
                             {"horizons", {0.05}}};
  const RunOutcome measured = run_scene(parse_scene(source, "test.json", "."), measured_dir);
  EXPECT_EQ(plain.summary["steps"], measured.summary["steps"]);
  EXPECT_EQ(plain.summary["energy_final"], measured.summary["energy_final"]);
  EXPECT_EQ(plain.summary["events"], measured.summary["events"]);
  EXPECT_EQ(measured.summary["restart_error"]["rows"], 2);  // the start and the release
  EXPECT_FALSE(fs::exists(plain_dir / "restart_error.csv"));
  EXPECT_TRUE(fs::exists(measured_dir / "restart_error.csv"));
}

TEST(ReferenceRestarts, BranchesOfARunThatDivergesAreReportedNotMeasured) {
  auto source = sheet(0.001);
  source["cloth"]["k_structural"] = 2000;
  const auto rows = [&] {
    source["integrator"] = {{"name", "symplectic-euler"}, {"dt", 0.02}};
    source["restart_error"] = {{"reference", {{"name", "leapfrog"}, {"dt", 1e-4}}},
                               {"horizons", {0.1, 0.2}}};
    const fs::path dir = fs::path(::testing::TempDir()) / "restarts_diverged";
    const RunOutcome outcome = run_scene(parse_scene(source, "test.json", "."), dir);
    EXPECT_EQ(outcome.summary["restart_error"]["rows_failed"], 2);
    return read_rows(dir / "restart_error.csv");
  }();
  ASSERT_EQ(rows.size(), 2u);
  for (const Row& row : rows) {
    EXPECT_EQ(row.status, "diverged");
    EXPECT_TRUE(std::isnan(row.error_rms));
  }
}

void expect_input_error(const nlohmann::json& restart_error, const std::string& field) {
  auto source = sheet(0.0);
  source["integrator"] = {{"name", "leapfrog"}, {"dt", 1e-3}};
  source["restart_error"] = restart_error;
  try {
    const Scene scene = parse_scene(source, "test.json", ".");
    run_scene(scene, fs::path(::testing::TempDir()) / "restarts_bad");
    ADD_FAILURE() << "accepted " << restart_error.dump();
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "test.json");
    EXPECT_EQ(e.field(), field) << e.what();
  }
}

TEST(ReferenceRestarts, BadInputNamesTheField) {
  const auto reference = nlohmann::json{{"name", "leapfrog"}, {"dt", 1e-4}};
  expect_input_error({{"reference", "leapfrog"}, {"horizons", {0.1}}},
                     "restart_error.reference");
  expect_input_error({{"reference", reference}, {"horizons", nlohmann::json::array()}},
                     "restart_error.horizons");
  expect_input_error({{"reference", reference}, {"horizons", {0.1, 0.05}}},
                     "restart_error.horizons[1]");
  expect_input_error({{"reference", reference}, {"horizons", {-0.1}}},
                     "restart_error.horizons[0]");
  expect_input_error({{"reference", reference}, {"horizons", {0.5}}},
                     "restart_error.horizons[0]");
  // Below duration x 2^-50 a horizon measures no motion.
  expect_input_error({{"reference", reference}, {"horizons", {1e-300, 0.1}}},
                     "restart_error.horizons[0]");
  expect_input_error({{"reference", reference}, {"horizons", {0.1}}, {"every", 2}},
                     "restart_error.every");
  expect_input_error({{"reference", {{"name", "leapfrg"}, {"dt", 1e-4}}}, {"horizons", {0.1}}},
                     "restart_error.reference.name");
  expect_input_error({{"reference", {{"name", "leapfrog"}, {"dt", 1e-30}}}, {"horizons", {0.1}}},
                     "restart_error.reference.dt");
}

}  // namespace
}  // namespace drape
