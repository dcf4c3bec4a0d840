// A damped pinned cloth settles at the static equilibrium found independently by Newton's method
// on the potential energy.
#include <gtest/gtest.h>

#include "integrators/explicit/leapfrog.hpp"
#include "integrators/explicit/symplectic_euler.hpp"
#include "tests/support/test_support.hpp"

namespace drape {
namespace {

template <class Method>
Eigen::VectorXd settle(ClothSystem& s, double dt) {
  Method method(s, dt);
  return testing::settle(method, s);
}

TEST(Equilibrium, DampedPinnedClothSettlesOnTheNewtonEquilibrium) {
  auto s = testing::pinned_test_cloth(0.02, 0.002);
  const Eigen::VectorXd expected = testing::newton_equilibrium(*s);
  // The cloth really sags: the equilibrium is far from the rest grid.
  EXPECT_GT((expected - s->cloth().rest_positions).lpNorm<Eigen::Infinity>(), 0.003);
  const Eigen::VectorXd leapfrog = settle<Leapfrog>(*s, 1e-3);
  EXPECT_LT((leapfrog - expected).lpNorm<Eigen::Infinity>(), 1e-8);
  const Eigen::VectorXd euler = settle<SymplecticEuler>(*s, 1e-3);
  EXPECT_LT((euler - expected).lpNorm<Eigen::Infinity>(), 1e-8);
}

}  // namespace
}  // namespace drape
