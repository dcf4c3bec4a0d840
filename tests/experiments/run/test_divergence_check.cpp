// The runaway bound that ends a diverged run (docs/outputs.md, summary.json): a free fall over
// the horizon, the energy a state holds, the fastest prescribed motion, each added in closed form.
#include "experiments/run/divergence_check.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "tests/support/test_support.hpp"

namespace drape {
namespace {

// A 3 x 3 cloth at rest: no spring stretched, no object, so its energy is kinetic only.
std::unique_ptr<ClothSystem> resting_cloth() {
  return std::make_unique<ClothSystem>(build_cloth(testing::small_cloth(3, 3)), nullptr,
                                       ForceParams{});
}

/// A state at rest with particle `i` moving at `speed` along z.
Eigen::VectorXd moving(const ClothSystem& s, int i, double speed) {
  Eigen::VectorXd y = s.initial_state(0.0);
  y[3 * s.num_particles() + 3 * i + 2] = speed;
  return y;
}

TEST(DivergenceCheck, TheBaseBoundIsTenPlusTwiceAFreeFall) {
  const auto s = resting_cloth();
  const DivergenceCheck check(9.81, 2.0);  // 10 + 2 * 9.81 * 2 = 49.24 m/s
  EXPECT_EQ(check.reason(*s, 0.0, s->initial_state(0.0)), "");
  EXPECT_EQ(check.reason(*s, 0.0, moving(*s, 4, 49.2)), "");
  EXPECT_EQ(check.reason(*s, 0.0, moving(*s, 4, -49.3)),
            "runaway: a particle moves at 49.3 m/s, above the bound 49.2 m/s");
}

TEST(DivergenceCheck, ANonFiniteStateIsNamedFirst) {
  const auto s = resting_cloth();
  const DivergenceCheck check(9.81, 1.0);
  Eigen::VectorXd y = s->initial_state(0.0);
  y[5] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(check.reason(*s, 0.0, y), "non-finite state");
  y[5] = std::numeric_limits<double>::infinity();
  EXPECT_EQ(check.reason(*s, 0.0, y), "non-finite state");
}

TEST(DivergenceCheck, StoredEnergyRaisesTheBoundByTheSpeedItCouldGiveOneParticle) {
  const auto s = resting_cloth();
  DivergenceCheck check(0.0, 0.0);  // base 10 m/s
  const Eigen::VectorXd start = moving(*s, 2, 30.0);
  const EnergyBreakdown e = energy_of(*s, start);
  EXPECT_NEAR(e.kinetic, 0.5 * s->particle_mass() * 900.0, 1e-15);
  EXPECT_NEAR(e.spring, 0.0, 1e-15);
  EXPECT_EQ(check.reason(*s, 0.0, start), "runaway: a particle moves at 30 m/s, above the bound 10 m/s");
  check.account_for(*s, e);  // all of it in one particle: sqrt(2 K / m) = 30 m/s
  EXPECT_EQ(check.reason(*s, 0.0, moving(*s, 7, 39.9)), "");
  EXPECT_NE(check.reason(*s, 0.0, moving(*s, 7, 40.1)), "");
  // Lower or negative energies later leave the bound where the largest put it.
  EnergyBreakdown negative;
  negative.kinetic = -1.0;
  check.account_for(*s, negative);
  check.account_for(*s, energy_of(*s, moving(*s, 2, 1.0)));
  EXPECT_EQ(check.reason(*s, 0.0, moving(*s, 7, 39.9)), "");
}

TEST(DivergenceCheck, PrescribedMotionCountsTwice) {
  auto s = resting_cloth();
  const DivergenceCheck check(0.0, 0.0);
  // A particle sliding at 5 m/s: the bound is 10 + 2 x 5 = 20 m/s.
  s->constraints().fix(
      0, std::make_shared<testing::LinearTrajectory>(Vec3::Zero(), Vec3(5.0, 0.0, 0.0)));
  EXPECT_EQ(check.reason(*s, 0.0, moving(*s, 8, 19.9)), "");
  EXPECT_EQ(check.reason(*s, 0.0, moving(*s, 8, 20.1)),
            "runaway: a particle moves at 20.1 m/s, above the bound 20 m/s");
}

}  // namespace
}  // namespace drape
