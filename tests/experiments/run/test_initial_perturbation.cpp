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

// Three particles in a row along x, 0.02 m apart, at rest.
Eigen::VectorXd row_of_three() {
  Eigen::VectorXd y = Eigen::VectorXd::Zero(18);
  for (int i = 0; i < 3; ++i) y[3 * i] = 0.02 * i;
  y[1] = y[4] = y[7] = 1.3;
  return y;
}

TEST(InitialPerturbation, StretchScalesEverySpringAboutTheOnePinWhichStays) {
  ConstraintSet pins(3);
  Eigen::VectorXd y = row_of_three();
  pins.fix_at(0, y.segment<3>(0));
  stretch_initial_positions(0.01, pins, y);
  EXPECT_EQ(y.segment<3>(0), Vec3(0.0, 1.3, 0.0)) << "the pin stays";
  EXPECT_NEAR((y.segment<3>(3) - y.segment<3>(0)).norm(), 0.0202, 1e-15);
  EXPECT_NEAR((y.segment<3>(6) - y.segment<3>(3)).norm(), 0.0202, 1e-15);
  EXPECT_EQ(y.tail(9).norm(), 0.0) << "at rest";
}

TEST(InitialPerturbation, StretchAboutThePinsCentroidMovesThePinsWithTheCloth) {
  // Pins at both ends: the middle particle stays, the pins move out and are fixed there, so no
  // spring is left at its rest length next to a pin.
  ConstraintSet pins(3);
  Eigen::VectorXd y = row_of_three();
  pins.fix_at(0, y.segment<3>(0));
  pins.fix_at(2, y.segment<3>(6));
  stretch_initial_positions(-0.05, pins, y);
  EXPECT_NEAR(y[0], 0.001, 1e-15);
  EXPECT_NEAR(y[3], 0.02, 1e-15);
  EXPECT_NEAR(y[6], 0.039, 1e-15);
  EXPECT_EQ(pins.trajectory(0)->position(1.0), Vec3(y.segment<3>(0)));
  EXPECT_EQ(pins.trajectory(2)->position(1.0), Vec3(y.segment<3>(6)));
  // Without pins the cloth's centroid stays.
  ConstraintSet free(3);
  Eigen::VectorXd z = row_of_three();
  stretch_initial_positions(0.05, free, z);
  EXPECT_NEAR(z[0], -0.001, 1e-15);
  EXPECT_NEAR(z[6], 0.041, 1e-15);
}

TEST(InitialPerturbation, VelocityWithinTheAmplitudeOnFreeParticlesOnlyAndSeeded) {
  Perturbation p;
  p.velocity = 2.0;
  p.seed = 5;
  ConstraintSet fixed(50);
  fixed.fix_at(4, Vec3::Zero());
  const Eigen::VectorXd y0 = Eigen::VectorXd::Zero(300);
  Eigen::VectorXd y = y0;
  perturb_initial_velocities(p, fixed, y);
  EXPECT_EQ(y.head(150).norm(), 0.0) << "positions unchanged";
  EXPECT_LE(y.tail(150).cwiseAbs().maxCoeff(), 2.0);
  EXPECT_GT(y.tail(150).cwiseAbs().maxCoeff(), 1.0) << "uses the amplitude";
  // The mean square of a uniform draw in [-a, a] is a^2 / 3; 147 draws give it within 20 %.
  EXPECT_NEAR(y.tail(150).squaredNorm() / 147.0, 4.0 / 3.0, 0.27);
  EXPECT_EQ(y.segment<3>(162).norm(), 0.0) << "a fixed particle keeps its trajectory's velocity";
  Eigen::VectorXd again = y0;
  perturb_initial_velocities(p, fixed, again);
  EXPECT_EQ(again, y) << "reproducible bit for bit";
  // The velocities do not depend on whether the positions are perturbed too.
  p.position = 1e-3;
  Eigen::VectorXd both = y0;
  perturb_initial_state(p, 0.02, fixed, both);
  EXPECT_EQ(both.tail(150), y.tail(150));
  EXPECT_GT(both.head(150).norm(), 0.0);
  p.seed = 6;
  Eigen::VectorXd other = y0;
  perturb_initial_velocities(p, fixed, other);
  EXPECT_GT((other - y).norm(), 1.0);
}

TEST(InitialPerturbation, NoStretchNoVelocityChangesNothing) {
  ConstraintSet pins(3);
  Eigen::VectorXd y = row_of_three();
  pins.fix_at(0, y.segment<3>(0));
  const Eigen::VectorXd y0 = y;
  perturb_initial_state(Perturbation{}, 0.02, pins, y);
  EXPECT_EQ(y, y0);
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
