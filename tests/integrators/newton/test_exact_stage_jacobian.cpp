// The exact stage Jacobian: its Newton direction solves the stage residual's linearisation,
// checked against finite differences of the residual (which holds every term the definite S
// drops: compressed springs' transverse stiffness and the damping direction's turning), with
// and without the Levenberg-Marquardt shift.
#include <gtest/gtest.h>

#include <algorithm>

#include "integrators/newton/exact_stage_jacobian.hpp"
#include "integrators/newton/incremental_potential.hpp"
#include "tests/support/swinging_sheet.hpp"

namespace drape {
namespace {

// Factorises A + shift M at a shaken, moving state z (so that springs are compressed and
// turning) and checks (dg/dv + shift M) d = -g, with dg/dv by central differences of the true
// residual (gradient() turns the damping directions with x).
void expect_direction_solves_linearised_stage(ExactStageJacobian& jacobian,
                                              const ClothSystem& system, ForceSplit split,
                                              double shift) {
  const Eigen::VectorXd a = testing::jitter(system.initial_state(0.0), 0.004, 3);
  const Eigen::Index n3 = a.size() / 2;
  IncrementalPotential potential(system, split);
  const double gamma = 0.02;
  Eigen::VectorXd z = a;
  potential.begin_stage(0.0, gamma, a, z);
  potential.state_of(testing::jitter(z.tail(n3), 0.5, 4), z);
  Eigen::VectorXd g(n3), d;
  potential.gradient(z, g);
  ASSERT_TRUE(jacobian.factorize(z.head(n3), z.tail(n3), gamma, shift));
  jacobian.newton_direction(g, d);
  for (const int i : system.constraints().fixed_particles())
    EXPECT_EQ(d.segment<3>(3 * i), Eigen::Vector3d::Zero());
  const double h = 1e-7;
  Eigen::VectorXd plus = z, minus = z, g_plus(n3), g_minus(n3);
  potential.state_of(z.tail(n3) + h * d, plus);
  potential.state_of(z.tail(n3) - h * d, minus);
  potential.gradient(plus, g_plus);
  potential.gradient(minus, g_minus);
  // d is zero on the fixed rows (above), where the shift does not apply.
  const Eigen::VectorXd linearised =
      (g_plus - g_minus) / (2 * h) + shift * system.particle_mass() * d;
  EXPECT_LT((linearised + g).lpNorm<Eigen::Infinity>(), 1e-6 * g.lpNorm<Eigen::Infinity>())
      << "shift " << shift;
}

TEST(ExactStageJacobian, NewtonDirectionSolvesTheLinearisedStage) {
  for (const ForceSplit split : {ForceSplit::all, ForceSplit::springs}) {
    auto system = testing::pinned_test_cloth(0.05, 0.01);
    ExactStageJacobian jacobian(*system, split);
    // One object for both shifts: the second factorisation reuses the first one's pattern.
    for (const double shift : {0.0, 0.7})
      expect_direction_solves_linearised_stage(jacobian, *system, split, shift);
  }
}

TEST(ExactStageJacobian, NewtonDirectionSolvesTheLinearisedStageInContact) {
  // The particle blocks (the smooth contact's Hessian, air damping) enter A's diagonal blocks:
  // a cloth against a sphere, with the contact in the implicit part or in all of it.
  auto system = testing::cloth_against_sphere(CollisionModel::smooth);
  JacobianBlocks blocks;
  const Eigen::VectorXd y = testing::jitter(system->initial_state(0.0), 0.004, 3);
  const Eigen::Index n3 = y.size() / 2;
  system->force_jacobian_blocks(y.head(n3), y.tail(n3), false, ForceSplit::all, blocks);
  const auto in_contact = std::count_if(blocks.particle_x.begin(), blocks.particle_x.end(),
                                        [](const Mat3& b) { return !b.isZero(); });
  ASSERT_GT(in_contact, 0) << "the test cloth must touch the sphere";
  for (const ForceSplit split : {ForceSplit::all, ForceSplit::springs_and_collision}) {
    ExactStageJacobian jacobian(*system, split);
    for (const double shift : {0.0, 0.7})
      expect_direction_solves_linearised_stage(jacobian, *system, split, shift);
  }
}

// BiCGSTAB on the formed matrix reaches the LU's direction at a tight tolerance (any
// preconditioner: here M^-1), and says so; within too few iterations it reports failure (the
// line search then factorises) and counts what it took.
TEST(ExactStageJacobian, KrylovDirectionMatchesTheFactorisedOne) {
  auto system = testing::pinned_test_cloth(0.05, 0.01);
  const Eigen::VectorXd a = testing::jitter(system->initial_state(0.0), 0.004, 3);
  const Eigen::Index n3 = a.size() / 2;
  IncrementalPotential potential(*system, ForceSplit::all);
  const double gamma = 0.02;
  Eigen::VectorXd z = a;
  potential.begin_stage(0.0, gamma, a, z);
  potential.state_of(testing::jitter(z.tail(n3), 0.5, 4), z);
  Eigen::VectorXd g(n3), lu, krylov;
  potential.gradient(z, g);
  ExactStageJacobian jacobian(*system, ForceSplit::all);
  for (const double shift : {0.0, 0.7}) {
    ASSERT_TRUE(jacobian.factorize(z.head(n3), z.tail(n3), gamma, shift));
    jacobian.newton_direction(g, lu);
    const double mass = system->particle_mass();
    const ExactStageJacobian::Preconditioner inverse_mass =
        [&](const Eigen::VectorXd& r, Eigen::VectorXd& out) {
          out = r / mass;
          system->constraints().zero_fixed(out);
        };
    long iterations = 0;
    ASSERT_TRUE(jacobian.krylov_direction(g, krylov, inverse_mass, 1e-12, 1000, iterations));
    EXPECT_GT(iterations, 1);
    EXPECT_LT((krylov - lu).norm(), 1e-8 * lu.norm()) << "shift " << shift;
    for (const int i : system->constraints().fixed_particles())
      EXPECT_EQ(krylov.segment<3>(3 * i), Eigen::Vector3d::Zero());
    long bounded = 0;
    EXPECT_FALSE(jacobian.krylov_direction(g, krylov, inverse_mass, 1e-12, 1, bounded));
    EXPECT_EQ(bounded, 1);
  }
}

TEST(ExactStageJacobian, FollowsAChangeOfTheFixedSet) {
  // The pattern (and UMFPACK's analysis) is built for one fixed set; pinning a free particle
  // and releasing a pinned one must rebuild it, or the direction would move the new pin.
  auto system = testing::pinned_test_cloth(0.05, 0.01);
  ExactStageJacobian jacobian(*system, ForceSplit::all);
  expect_direction_solves_linearised_stage(jacobian, *system, ForceSplit::all, 0.0);
  const int pinned = system->constraints().fixed_particles().front();
  const int freed = system->num_particles() / 2 + 1;
  ASSERT_FALSE(system->constraints().is_fixed(freed));
  system->constraints().fix_at(freed, Vec3(0.1, 0.2, 0.3));
  system->constraints().release(pinned);
  expect_direction_solves_linearised_stage(jacobian, *system, ForceSplit::all, 0.0);
}

}  // namespace
}  // namespace drape
