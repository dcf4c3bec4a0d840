// The exact stage Jacobian: its Newton direction solves the stage residual's linearisation,
// checked against finite differences of the residual (which holds every term the definite S
// drops: compressed springs' transverse stiffness and the damping direction's turning), with
// and without the Levenberg-Marquardt shift.
#include <gtest/gtest.h>

#include "integrators/newton/exact_stage_jacobian.hpp"
#include "integrators/newton/incremental_potential.hpp"
#include "tests/support/swinging_sheet.hpp"

namespace drape {
namespace {

TEST(ExactStageJacobian, NewtonDirectionSolvesTheLinearisedStage) {
  for (const ForceSplit split : {ForceSplit::all, ForceSplit::springs}) {
    for (const double shift : {0.0, 0.7}) {
      // A damped pinned cloth, shaken and moving, so that springs are compressed and turning.
      auto system = testing::pinned_test_cloth(0.05, 0.01);
      const Eigen::VectorXd a = testing::jitter(system->initial_state(0.0), 0.004, 3);
      const Eigen::Index n3 = a.size() / 2;
      IncrementalPotential potential(*system, split);
      const double gamma = 0.02;
      Eigen::VectorXd z = a;
      potential.begin_stage(0.0, gamma, a, z);
      potential.state_of(testing::jitter(z.tail(n3), 0.5, 4), z);
      Eigen::VectorXd g(n3), d;
      potential.gradient(z, g);
      ExactStageJacobian jacobian(*system, split);
      ASSERT_TRUE(jacobian.factorize(z.head(n3), z.tail(n3), gamma, shift));
      jacobian.newton_direction(g, d);
      for (const int i : system->constraints().fixed_particles())
        EXPECT_EQ(d.segment<3>(3 * i), Eigen::Vector3d::Zero());
      // (dg/dv + shift M) d = -g, with dg/dv by central differences of the true residual
      // (gradient() turns the damping directions with x).
      const double h = 1e-7;
      Eigen::VectorXd plus = z, minus = z, g_plus(n3), g_minus(n3);
      potential.state_of(z.tail(n3) + h * d, plus);
      potential.state_of(z.tail(n3) - h * d, minus);
      potential.gradient(plus, g_plus);
      potential.gradient(minus, g_minus);
      // d is zero on the fixed rows (above), where the shift does not apply.
      const Eigen::VectorXd linearised =
          (g_plus - g_minus) / (2 * h) + shift * system->particle_mass() * d;
      EXPECT_LT((linearised + g).lpNorm<Eigen::Infinity>(), 1e-6 * g.lpNorm<Eigen::Infinity>())
          << "shift " << shift;
    }
  }
}

}  // namespace
}  // namespace drape
