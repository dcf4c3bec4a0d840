// A sweep of block Newton steps never raises backward Euler's incremental potential: each block
// step is halved until its exact change of G is not positive (vertex_block_descent.hpp).
#include <gtest/gtest.h>

#include "integrators/vbd/vertex_block_descent.hpp"
#include "tests/support/swinging_sheet.hpp"
#include "tests/support/test_support.hpp"

namespace drape {
namespace {

constexpr double h = 1.0 / 30.0;

// Sweeps from y + h^2 g on a moving state. With spring damping the directions u are frozen at
// each sweep's start (as Newton freezes them at its iterate), so G changes from sweep to sweep:
// what holds is G_k(x_(k+1)) <= G_k(x_k). Without spring damping G is one function and falls
// monotonically over all sweeps (pinned_test_cloth below). `magnitude` bounds G's summation
// round-off.
void expect_descent(ClothSystem& s, int sweeps) {
  const Eigen::Index n3 = 3 * s.num_particles();
  const Eigen::VectorXd x_n = testing::jitter(s.initial_state(0.0).head(n3), 0.003, 7);
  const Eigen::VectorXd v_n = testing::jitter(Eigen::VectorXd::Zero(n3), 0.1, 8);
  VertexBlockDescent descent(s);
  descent.begin_step(h, x_n, v_n);
  Eigen::VectorXd x = x_n + h * v_n;
  for (int i = 0; i < s.num_particles(); ++i) {
    if (s.constraints().is_fixed(i))
      particle(x, i) = s.constraints().trajectory(i)->position(h);
    else
      particle(x, i) += h * h * s.params().gravity;
  }
  VertexBlockPotential& g = descent.potential();
  g.freeze_directions(x);
  const double first = g.value(x);
  const double magnitude = 1e-13 * (std::abs(first) + 1.0);
  double previous = first;
  for (int k = 0; k < sweeps; ++k) {
    g.freeze_directions(x);
    const double before = g.value(x);
    descent.sweep(x);
    const double after = g.value(x);
    EXPECT_LE(after, before + magnitude) << "sweep " << k;
    previous = after;
  }
  EXPECT_LT(previous, first - 1e3 * magnitude) << "the sweeps made progress";
}

TEST(VertexBlockDescent, SweepsNeverRaiseThePotential) {
  auto sheet = testing::swinging_sheet(1.0);
  expect_descent(*sheet, 30);
  expect_descent(*testing::pinned_test_cloth(0.0, 0.01), 30);
  expect_descent(*testing::cloth_against_sphere(CollisionModel::smooth), 30);
  expect_descent(*testing::cloth_against_sphere(CollisionModel::particle), 30);
}

}  // namespace
}  // namespace drape
