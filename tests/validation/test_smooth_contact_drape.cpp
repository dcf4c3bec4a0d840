// A cloth dropped with the `smooth` collision model onto a sphere and onto the dress form, with
// leap-frog at a small step and implicit Euler at 1/30 s: it comes to rest on the surface, with
// no particle inside it, and the particle that lands first stays on top.
#include <gtest/gtest.h>

#include "core/dummy/smooth_surface.hpp"
#include "core/scene/scene.hpp"
#include "experiments/run/scene_simulation.hpp"

namespace drape {
namespace {

struct Drop {
  double lowest_gap;   // smallest smooth gap over the cloth at the end
  double centre_gap;   // gap of the particle above the top
  double centre_y;
};

Drop drop(const nlohmann::json& dummy, const nlohmann::json& origin, const nlohmann::json& integrator,
          int centre) {
  nlohmann::json source = nlohmann::json::parse(R"({
    "cloth": {"rows": 11, "cols": 11, "spacing": 0.03, "row_dir": [0, 0, 1],
              "particle_mass": 0.001, "k_structural": 30, "damping_spring": 0.005,
              "damping_air": 0.002},
    "collision": {"threshold": 0.01, "stiffness": 200, "model": "smooth"},
    "duration": 0.6})");
  source["cloth"]["origin"] = origin;
  source["dummy"] = dummy;
  source["integrator"] = integrator;
  SceneSimulation run(parse_scene(source, "drop.json", "."));
  const RunStatus& status = run.simulation().run();
  EXPECT_EQ(status.status, "ok") << status.reason;
  const SmoothSurface surface(run.system().dummy()->sections());
  const Eigen::VectorXd& y = run.simulation().state();
  Drop out{1e9, surface.gap(y.segment<3>(3 * centre)).gap, y[3 * centre + 1]};
  for (int i = 0; i < 121; ++i) out.lowest_gap = std::min(out.lowest_gap, surface.gap(y.segment<3>(3 * i)).gap);
  return out;
}

// DISABLED: fails on this branch (docs/model.md section 4.11 has the open points). Leap-frog at
// 0.2 ms diverges on the sphere (a particle at 65 m/s: the slope-scaled gap near the pole is
// still stiff for an explicit step), implicit Euler leaves the centre 1.8 cm above the top; on
// the dress form the cloth slides off the neck and shoulders (centre at y = 0.99 m).
TEST(SmoothContactDrape, DISABLED_ClothComesToRestOnASphereWithNoParticleInside) {
  const nlohmann::json sphere{{"builtin", "sphere"}, {"radius", 0.15}, {"center", {0.0, 0.5, 0.0}}};
  for (const auto& integrator : {nlohmann::json{{"name", "leapfrog"}, {"dt", 2e-4}},
                                 nlohmann::json{{"name", "implicit-euler"}, {"dt", 1.0 / 30}}}) {
    const Drop d = drop(sphere, {-0.15, 0.68, -0.15}, integrator, 60);
    EXPECT_GE(d.lowest_gap, 0.0) << integrator;
    EXPECT_LT(d.centre_gap, 0.01) << integrator << ": the centre rests on the top";
    EXPECT_GT(d.centre_y, 0.64) << integrator;
  }
}

TEST(SmoothContactDrape, DISABLED_ClothComesToRestOnTheDressFormWithNoParticleInside) {
  // Over the shoulders, centred on the neck.
  for (const auto& integrator : {nlohmann::json{{"name", "leapfrog"}, {"dt", 2e-4}},
                                 nlohmann::json{{"name", "implicit-euler"}, {"dt", 1.0 / 30}}}) {
    const Drop d = drop({{"builtin", "dress-form"}}, {-0.15, 1.40, -0.15}, integrator, 60);
    EXPECT_GE(d.lowest_gap, 0.0) << integrator;
    EXPECT_LT(d.centre_gap, 0.01) << integrator;
    EXPECT_GT(d.centre_y, 1.30) << integrator;
  }
}

}  // namespace
}  // namespace drape
