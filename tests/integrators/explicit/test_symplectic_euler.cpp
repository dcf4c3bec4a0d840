// Symplectic Euler (kick, then drift) against its recursion in closed form: a particle in free
// fall, x_n = x_0 + n h v_0 + h^2 g n (n + 1) / 2, and a linear spring, whose step map
// [x; v] -> [x + h v'; v'], v' = v - h w^2 x, keeps x^2 w^2 + v^2 - h w^2 x v constant.
#include "integrators/explicit/symplectic_euler.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/support/test_support.hpp"

namespace drape {
namespace {

TEST(SymplecticEuler, FreeFallFollowsTheRecursionNotTheParabola) {
  ClothSystem s(build_cloth(testing::small_cloth(1, 1)), nullptr, ForceParams{});
  Eigen::VectorXd y0 = s.initial_state(0.0);
  y0.tail(3) = Vec3(0.5, 0.0, 0.0);
  const double h = 0.01;
  SymplecticEuler method(s, h);
  method.reset(0.0, y0);
  const int n = 20;
  for (int k = 0; k < n; ++k) method.step(1.0);
  const Vec3 g(0.0, -9.81, 0.0);
  const Vec3 x = y0.head<3>() + n * h * y0.tail<3>() + h * h * g * (n * (n + 1) / 2.0);
  EXPECT_LT((method.state().head<3>() - x).norm(), 1e-14);
  EXPECT_LT((method.state().tail<3>() - (y0.tail<3>() + n * h * g)).norm(), 1e-14);
  // Kicking first, it falls h^2 |g| n / 2 further than the exact parabola: a first-order error.
  const double exact_y = y0[1] - 0.5 * 9.81 * std::pow(n * h, 2);
  EXPECT_NEAR(method.state()[1] - exact_y, -0.5 * 9.81 * h * h * n, 1e-14);
  EXPECT_EQ(method.counters().rhs_evals, n) << "one force evaluation a step";
  EXPECT_EQ(method.counters().steps, n);
}

TEST(SymplecticEuler, ALinearSpringKeepsTheModifiedEnergy) {
  // Two particles along x, the first pinned, one structural spring of rest length 2 cm, no
  // gravity: the free particle's stretch u obeys u'' = -(k / m) u exactly.
  ClothParams p = testing::small_cloth(1, 2);
  p.k_shear = p.k_bending = 0.0;
  ForceParams forces;
  forces.gravity = Vec3::Zero();
  ClothSystem s(build_cloth(p), nullptr, forces);
  s.constraints().fix_at(0, s.cloth().rest_positions.head<3>());
  Eigen::VectorXd y = s.initial_state(0.0);
  y[3] += 0.001;  // stretched by 1 mm
  const double w2 = p.k_structural / p.particle_mass, h = 0.1 / std::sqrt(w2);
  const auto invariant = [&](const Eigen::VectorXd& state) {
    const double u = state[3] - 0.02 - p.origin.x(), v = state[9];
    return w2 * u * u + v * v - h * w2 * u * v;
  };
  SymplecticEuler method(s, h);
  method.reset(0.0, y);
  const double start = invariant(y);
  for (int k = 0; k < 500; ++k) {
    method.step(1e9);
    ASSERT_NEAR(invariant(method.state()), start, 1e-12 * start) << "step " << k;
  }
  EXPECT_EQ(method.state().segment<3>(0), s.cloth().rest_positions.head<3>()) << "the pin holds";
}

}  // namespace
}  // namespace drape
