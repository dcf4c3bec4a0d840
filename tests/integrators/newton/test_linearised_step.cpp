// One linearised implicit step, (I - gamma J) dy = gamma f + d (Baraff and Witkin 1998,
// section 4), where it has a closed form: particles without springs under gravity and air
// damping, J = [0 I; 0 -c/m], so (1 + gamma c / m) dv = gamma (g - c v / m) + d_v and
// dx = gamma (v + dv) + d_x; a fixed particle lands on its trajectory at t + h.
#include "integrators/newton/linearised_step.hpp"

#include <gtest/gtest.h>

#include "tests/support/test_support.hpp"

namespace drape {
namespace {

// Two particles with no spring (every stiffness 0), air damping c, the first sliding at 0.3 m/s
// along x.
struct Falling {
  ClothParams params = [] {
    ClothParams p = testing::small_cloth(1, 2);
    p.k_structural = p.k_shear = p.k_bending = 0.0;
    p.damping_air = 0.002;
    return p;
  }();
  ClothSystem system{build_cloth(params), nullptr, ForceParams{}};
  ReducedNewtonSolver solver{system, ReducedSolve::sparse_ldlt, ForceSplit::all, 1e-12, 100};
  Falling() {
    system.constraints().fix(0, std::make_shared<testing::LinearTrajectory>(
                                    Vec3(0.0, 1.0, 0.0), Vec3(0.3, 0.0, 0.0)));
  }
};

TEST(LinearisedStep, BackwardEulerHasItsClosedForm) {
  Falling f;
  Eigen::VectorXd y = f.system.initial_state(0.0);
  const Vec3 v0(0.1, -0.2, 0.05);
  y.segment<3>(9) = v0;
  const Vec3 x0 = y.segment<3>(3);
  const double h = 0.01, t = 0.5, c_over_m = f.params.damping_air / f.params.particle_mass;
  IntegratorCounters counters;
  LinearisedStep(f.system, f.solver).take(t, h, h, nullptr, y, counters);
  const Vec3 g(0.0, -9.81, 0.0);
  const Vec3 dv = h * (g - c_over_m * v0) / (1.0 + h * c_over_m);
  EXPECT_LT((y.segment<3>(9) - (v0 + dv)).norm(), 1e-14);
  EXPECT_LT((y.segment<3>(3) - (x0 + h * (v0 + dv))).norm(), 1e-14);
  // The fixed particle is on its trajectory at t + h, whatever it was at t.
  EXPECT_LT((y.segment<3>(0) - Vec3(0.3 * (t + h), 1.0, 0.0)).norm(), 1e-14);
  EXPECT_LT((y.segment<3>(6) - Vec3(0.3, 0.0, 0.0)).norm(), 1e-14);
  EXPECT_EQ(counters.rhs_evals, 1);
  EXPECT_EQ(counters.jacobian_setups, 1);
  EXPECT_EQ(counters.newton_iters, 1);
  EXPECT_EQ(counters.linear_iters, 0) << "a direct solve";
  EXPECT_EQ(counters.convergence_failures, 0);
}

TEST(LinearisedStep, TheHistoryTermIsAddedToTheRightHandSide) {
  Falling f;
  Eigen::VectorXd y = f.system.initial_state(0.0);
  const Vec3 x0 = y.segment<3>(3), v0 = y.segment<3>(9);
  const double h = 0.02, gamma = 2.0 / 3.0 * h, c_over_m = f.params.damping_air / f.params.particle_mass;
  Eigen::VectorXd history = Eigen::VectorXd::Zero(12);  // BDF2's (y_n - y_{n-1}) / 3
  history.segment<3>(3) = Vec3(1e-3, 0.0, -2e-3);
  history.segment<3>(9) = Vec3(0.0, 0.05, 0.0);
  history.segment<3>(0) = Vec3(7.0, 7.0, 7.0);  // a fixed particle's rows are its trajectory's
  IntegratorCounters counters;
  LinearisedStep(f.system, f.solver).take(0.0, h, gamma, &history, y, counters);
  const Vec3 g(0.0, -9.81, 0.0);
  const Vec3 dv = (gamma * (g - c_over_m * v0) + history.segment<3>(9)) / (1.0 + gamma * c_over_m);
  EXPECT_LT((y.segment<3>(9) - (v0 + dv)).norm(), 1e-14);
  EXPECT_LT((y.segment<3>(3) - (x0 + gamma * (v0 + dv) + history.segment<3>(3))).norm(), 1e-14);
  EXPECT_LT((y.segment<3>(0) - Vec3(0.3 * h, 1.0, 0.0)).norm(), 1e-14);
}

}  // namespace
}  // namespace drape
