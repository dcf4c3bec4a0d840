// The seeded initial perturbation of ensembles (docs/scene.md `perturbation`).
#include <gtest/gtest.h>

#include "experiments/run/initial_perturbation.hpp"

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

}  // namespace
}  // namespace drape
