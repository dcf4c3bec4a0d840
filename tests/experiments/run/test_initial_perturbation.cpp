// The seeded initial perturbation of ensembles (docs/scene.md `perturbation`), and its
// repetition after a map (perturbation.after_map), which otherwise erases it.
#include <gtest/gtest.h>

#include "core/scene/scene.hpp"
#include "experiments/run/initial_perturbation.hpp"
#include "experiments/run/scene_simulation.hpp"

namespace drape {
namespace {

Eigen::VectorXd perturbed(const Perturbation& p, const ConstraintSet& fixed, int n = 50) {
  Eigen::VectorXd y = Eigen::VectorXd::LinSpaced(6 * n, 0.0, 1.0);
  perturb_initial_positions(p, 0.02, fixed, y);
  return y;
}

TEST(InitialPerturbation, ZeroByDefaultChangesNothing) {
  const Eigen::VectorXd y = Eigen::VectorXd::LinSpaced(300, 0.0, 1.0);
  EXPECT_EQ(perturbed(Perturbation{}, ConstraintSet(50)), y);
}

TEST(InitialPerturbation, SameSeedSameStateOtherSeedOtherState) {
  Perturbation p;
  p.position = 1e-3;
  p.seed = 7;
  const ConstraintSet free(50);
  EXPECT_EQ(perturbed(p, free), perturbed(p, free)) << "reproducible bit for bit";
  Perturbation q = p;
  q.seed = 8;
  EXPECT_GT((perturbed(p, free) - perturbed(q, free)).norm(), 1e-6);
  p.gaussian = q.gaussian = true;
  EXPECT_EQ(perturbed(p, free), perturbed(p, free));
  EXPECT_GT((perturbed(p, free) - perturbed(q, free)).norm(), 1e-6);
}

TEST(InitialPerturbation, UniformWithinTheAmplitudeOnFreePositionsOnly) {
  Perturbation p;
  p.position = 1e-3;
  p.seed = 3;
  ConstraintSet fixed(50);
  fixed.fix_at(4, Vec3::Zero());
  const Eigen::VectorXd y0 = Eigen::VectorXd::LinSpaced(300, 0.0, 1.0);
  const Eigen::VectorXd d = perturbed(p, fixed) - y0;
  EXPECT_LE(d.head(150).cwiseAbs().maxCoeff(), 1e-3 * 0.02);
  EXPECT_GT(d.head(150).cwiseAbs().maxCoeff(), 0.5e-3 * 0.02) << "uses the amplitude";
  EXPECT_EQ(d.segment<3>(12).norm(), 0.0) << "fixed particles stay on their trajectory";
  EXPECT_EQ(d.tail(150).norm(), 0.0) << "velocities unchanged";
  // The other particles draw the same numbers whether particle 4 is fixed or not.
  const Eigen::VectorXd all = perturbed(p, ConstraintSet(50)) - y0;
  EXPECT_EQ(d.head(12), all.head(12));
  EXPECT_EQ(d.segment(15, 135), all.segment(15, 135));
}

TEST(InitialPerturbation, EachStreamItsOwnAndStreamZeroTheInitialOne) {
  Perturbation p;
  p.position = 1e-3;
  p.seed = 7;
  const ConstraintSet free(50);
  const Eigen::VectorXd y0 = Eigen::VectorXd::LinSpaced(300, 0.0, 1.0);
  Eigen::VectorXd s0 = y0, s1 = y0, s2 = y0;
  perturb_positions(p, 0, 0.02, free, s0);
  perturb_positions(p, 1, 0.02, free, s1);
  perturb_positions(p, 2, 0.02, free, s2);
  EXPECT_EQ(s0, perturbed(p, free));
  EXPECT_GT((s1 - s0).norm(), 1e-6);
  EXPECT_GT((s2 - s1).norm(), 1e-6);
  EXPECT_LE((s1 - y0).cwiseAbs().maxCoeff(), 1e-3 * 0.02);
}

// The state 10 ms after a map at t = 0.01 s of a small cloth on the dress form (leap-frog).
Eigen::VectorXd after_map(int seed, bool again) {
  auto source = nlohmann::json::parse(R"({
    "cloth": {"rows": 6, "cols": 6, "spacing": 0.02, "origin": [0.0, 1.25, 0.30],
              "particle_mass": 6e-5, "k_structural": 50, "damping_spring": 0.05},
    "collision": {"threshold": 0.02, "stiffness": 20},
    "integrator": {"name": "leapfrog", "dt": 2e-4},
    "input": {"events": [{"t": 0.01, "keys": ["m"]}]},
    "manipulation": {"map_top": 1.25}, "duration": 0.02})");
  source["perturbation"] = {{"position", 1e-3}, {"seed", seed}, {"after_map", again}};
  SceneSimulation run(parse_scene(source, "test.json", "."));
  EXPECT_EQ(run.simulation().run().status, "ok");
  EXPECT_EQ(run.simulation().manipulator().events().at(0).type, "map");
  return run.simulation().state();
}

TEST(InitialPerturbation, AfterAMapOnlyAfterMapKeepsTheRepeatsApart) {
  // The map lays every particle out anew: without after_map two seeds end bit for bit alike.
  EXPECT_EQ(after_map(1, false), after_map(2, false));
  const Eigen::VectorXd one = after_map(1, true);
  EXPECT_EQ(one, after_map(1, true)) << "reproducible";
  const double apart = (one - after_map(2, true)).head(108).cwiseAbs().maxCoeff();
  EXPECT_GT(apart, 1e-7);
  EXPECT_LT(apart, 1e-3) << "a perturbation, not another run";
}

}  // namespace
}  // namespace drape
