// The line-search Newton on the swinging sheet's hard stage: a backward-Euler step of 1/30 s of the
// horizontal sheet at 100x stiffness, where plain Newton diverges.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "integrators/newton/line_search_newton.hpp"
#include "tests/support/swinging_sheet.hpp"

namespace drape {
namespace {

struct HardStep {
  std::unique_ptr<ClothSystem> system = testing::swinging_sheet(100.0);
  ReducedNewtonSolver solver{*system, ReducedSolve::multigrid_cg, ForceSplit::all, 1e-8, 500};
  LineSearchNewton newton{*system, ForceSplit::all, solver};
  Eigen::VectorXd a = system->initial_state(0.0);
  Eigen::VectorXd weights = 1.0 / (1e-4 * a.array().abs() + 1e-7);
  double gamma = 1.0 / 30.0;

  StageSolve solve(Eigen::VectorXd& z, int max_iterations) {
    z = a;
    return newton.solve(gamma, gamma, a, z, StageTolerance{weights, 0.1, max_iterations});
  }
  /// |z - a - gamma f(t, z)| relative to |gamma f(t, z)| (max norms): the stage equation's error.
  double relative_stage_residual(const Eigen::VectorXd& z) const {
    Eigen::VectorXd f(z.size());
    system->rhs(gamma, z, f);
    return (z - a - gamma * f).lpNorm<Eigen::Infinity>() / (gamma * f).lpNorm<Eigen::Infinity>();
  }
};

TEST(LineSearchNewton, SolvesTheHardBackwardEulerStep) {
  HardStep step;
  Eigen::VectorXd z;
  const StageSolve result = step.solve(z, 200);
  ASSERT_TRUE(result.converged) << result.iterations << " iterations";
  EXPECT_GT(result.iterations, 3);  // the hard step: not ARKODE's default 3
  // The stage equation holds: z = a + gamma f(t, z).
  EXPECT_LT(step.relative_stage_residual(z), 1e-5);
}

// Each iteration's step never raises the potential frozen at its start (Armijo's condition).
TEST(LineSearchNewton, LineSearchNeverIncreasesTheMerit) {
  HardStep step;
  Eigen::VectorXd full;
  const int iterations = step.solve(full, 200).iterations;
  ASSERT_GT(iterations, 3);
  long backtracks = 0;
  Eigen::VectorXd before, after;
  // The first iterations, where plain Newton's residual grows (each k re-solves from the start).
  for (int k = 1; k < std::min(iterations, 8); ++k) {
    step.solve(before, k - 1);  // 0 iterations: the stage's start
    const StageSolve r = step.solve(after, k);
    backtracks = r.backtracks;
    // The potential of the stage, frozen at the iterate that iteration k starts from.
    IncrementalPotential merit(*step.system, ForceSplit::all);
    Eigen::VectorXd start = step.a;
    merit.begin_stage(step.gamma, step.gamma, step.a, start);
    merit.freeze_damping(before);
    EXPECT_LE(merit.value(after), merit.value(before)) << "iteration " << k;
  }
  EXPECT_GT(backtracks, 0);  // the hard step needs the line search
}

// A stage from a buckled state: the stiff sheet compressed by 10 % in its plane and shaken out of
// it. The compressed springs' negative transverse stiffness makes the exact stage Jacobian A
// indefinite, so that its Newton direction need not descend on E_k, or overshoots; the
// Levenberg-Marquardt shift (line_search_newton.cpp) keeps the local phase on A's directions.
TEST(LineSearchNewton, SolvesAStageWhoseJacobianIsIndefinite) {
  HardStep step;
  const Eigen::Index n3 = step.a.size() / 2, n = n3 / 3;
  Eigen::Map<Eigen::Matrix3Xd> points(step.a.data(), 3, n);
  const Vec3 centre = points.rowwise().mean();
  points = (0.9 * (points.colwise() - centre)).colwise() + centre;
  step.a.head(n3) = testing::jitter(step.a.head(n3), 2e-4, 7);
  step.system->constraints().project(0.0, VecMap(step.a.data(), n3),
                                     VecMap(step.a.data() + n3, n3));
  Eigen::VectorXd z;
  const StageSolve result = step.solve(z, 200);
  ASSERT_TRUE(result.converged) << result.iterations << " iterations";
  // The case the shift exists for (92 of 131 directions were shifted when this was written).
  EXPECT_GT(result.shifted_directions, 0);
  EXPECT_LT(step.relative_stage_residual(z), 1e-5);
}

}  // namespace
}  // namespace drape
