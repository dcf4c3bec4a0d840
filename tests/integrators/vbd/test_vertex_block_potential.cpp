// VBD's per-particle block of backward Euler's incremental potential: gradient and Hessian
// against finite differences of G, the energy change against differences of G, and G's
// minimiser against the converged Newton solve's stage equation.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include "integrators/vbd/vertex_block_potential.hpp"
#include "tests/support/swinging_sheet.hpp"
#include "tests/support/test_support.hpp"

namespace drape {
namespace {

constexpr double h = 1.0 / 30.0;

// A step of `s` from a jittered, moving state; positions x jittered again (the iterate).
struct StepState {
  Eigen::VectorXd x_n, v_n, x;
};

StepState moving_state(const ClothSystem& s, unsigned seed) {
  const Eigen::Index n3 = 3 * s.num_particles();
  StepState out;
  out.x_n = testing::jitter(s.initial_state(0.0).head(n3), 0.002, seed);
  out.v_n = testing::jitter(Eigen::VectorXd::Zero(n3), 0.05, seed + 1);
  out.x = testing::jitter(out.x_n + h * out.v_n, 0.002, seed + 2);
  return out;
}

// -grad_i G and the exact block Hessian (definite = false) against central differences of G
// with the damping directions frozen at x, on free particles of the damped sheet and of a
// cloth pressed on a sphere (smooth contact: its C2 potential).
void expect_block_matches_differences(ClothSystem& s, unsigned seed) {
  const StepState st = moving_state(s, seed);
  VertexBlockPotential g(s);
  g.begin_step(h, st.x_n, st.v_n);
  g.freeze_directions(st.x);
  const double eps = 1e-6;
  int checked = 0;
  for (int i = 0; i < s.num_particles(); ++i) {
    if (s.constraints().is_fixed(i)) continue;
    const VertexBlock b = g.block(i, st.x.data(), false);
    auto value_at = [&](const Vec3& dx) {
      Eigen::VectorXd x = st.x;
      particle(x, i) += dx;
      return g.value(x);
    };
    Vec3 gradient;
    Mat3 hessian;
    for (int a = 0; a < 3; ++a) {
      const Vec3 ea = eps * Vec3::Unit(a);
      gradient[a] = (value_at(ea) - value_at(-ea)) / (2 * eps);
      for (int c = 0; c < 3; ++c) {
        const Vec3 ec = eps * Vec3::Unit(c);
        hessian(a, c) =
            (value_at(ea + ec) - value_at(ea - ec) - value_at(-ea + ec) + value_at(-ea - ec)) /
            (4 * eps * eps);
      }
    }
    EXPECT_LT((gradient + b.force).norm(), 1e-6 * b.force.norm() + 1e-9) << "particle " << i;
    EXPECT_LT((hessian - b.hessian).norm(), 1e-4 * b.hessian.norm()) << "particle " << i;
    // The definite block is at least M / h^2.
    const Mat3 definite = g.block(i, st.x.data(), true).hessian;
    const double smallest = Eigen::SelfAdjointEigenSolver<Mat3>(definite).eigenvalues()[0];
    EXPECT_GE(smallest, s.particle_mass() / (h * h) * (1.0 - 1e-12)) << "particle " << i;
    ++checked;
  }
  EXPECT_EQ(checked,
            s.num_particles() - static_cast<int>(s.constraints().fixed_particles().size()));
}

TEST(VertexBlockPotential, BlockMatchesFiniteDifferencesOfThePotential) {
  expect_block_matches_differences(*testing::swinging_sheet(1.0, 6), 3);
  expect_block_matches_differences(*testing::cloth_against_sphere(CollisionModel::smooth), 5);
}

// energy_change equals the difference of G's values (which it computes without cancellation).
TEST(VertexBlockPotential, EnergyChangeIsTheDifferenceOfThePotential) {
  for (auto& s :
       {testing::swinging_sheet(1.0, 6), testing::cloth_against_sphere(CollisionModel::smooth)}) {
    const StepState st = moving_state(*s, 11);
    VertexBlockPotential g(*s);
    g.begin_step(h, st.x_n, st.v_n);
    g.freeze_directions(st.x);
    const double start = g.value(st.x);
    for (int i = 1; i < s->num_particles(); i += 3) {
      const Vec3 dx(1e-3, -2e-3, 5e-4);
      Eigen::VectorXd moved = st.x;
      particle(moved, i) += dx;
      const double expected = g.value(moved) - start;
      double magnitude = 0.0;
      EXPECT_NEAR(g.energy_change(i, st.x.data(), dx, magnitude), expected, 1e-9 * std::abs(start))
          << "particle " << i;
    }
  }
}

}  // namespace
}  // namespace drape
