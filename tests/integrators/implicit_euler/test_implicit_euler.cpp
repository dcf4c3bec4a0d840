// Baraff-Witkin implicit Euler: first order, stable far beyond the explicit limit, settles on
// the equilibrium, keeps fixed particles on their paths.
#include <gtest/gtest.h>

#include "integrators/implicit_euler/implicit_euler.hpp"
#include "integrators/registry/registry.hpp"
#include "tests/support/swinging_sheet.hpp"
#include "tests/support/test_support.hpp"

namespace drape {
namespace {

IntegratorOptions euler_options(double dt, const std::string& linear_solver = "pcg-reduced") {
  IntegratorOptions o;
  o.name = "implicit-euler";
  o.dt = dt;
  o.linear_solver = linear_solver;
  o.linear_tolerance = 1e-12;
  o.max_linear_iters = 1000;
  return o;
}

// Converged backward Euler at 1/30 s on the multigrid CG, the stiff-sheet tests' method; with
// `tight`, tolerances small enough to check its step equation.
IntegratorOptions converged_options(bool tight) {
  IntegratorOptions o = euler_options(1.0 / 30.0, "pcg-multigrid");
  o.solve = "converged";
  if (tight) {
    o.rtol = 1e-8;
    o.atol = 1e-10;
  }
  return o;
}

Eigen::VectorXd run(ClothSystem& s, const IntegratorOptions& o, const Eigen::VectorXd& y0,
                    double t_end) {
  ImplicitEuler method(s, o);
  method.reset(0.0, y0);
  return testing::run_until(method, t_end);
}

TEST(ImplicitEuler, TrajectoryIsFirstOrder) {
  auto s = testing::pinned_test_cloth();
  const Eigen::VectorXd y0 = testing::shaken_state(*s);
  const double t_end = 0.1;
  // The exact trajectory to far below these errors: an order-8 Runge-Kutta at a small step
  // (40 times cheaper than implicit Euler at 1e-6 s, whose own error biased the fit).
  IntegratorOptions exact;
  exact.name = "arkode-erk";
  exact.table = "ARKODE_FEHLBERG_13_7_8";
  exact.dt = 2.5e-5;
  auto reference_method = make_integrator(exact, *s);
  reference_method->reset(0.0, y0);
  const Eigen::VectorXd reference = testing::run_until(*reference_method, t_end);
  for (const char* solver : {"pcg-reduced", "pcg-multigrid", "sparse-direct"}) {
    std::vector<double> dts, errors;
    for (int k = 0; k < 4; ++k) {
      dts.push_back(1e-4 / (1 << k));
      const Eigen::VectorXd y = run(*s, euler_options(dts.back(), solver), y0, t_end);
      errors.push_back((y - reference).head(y.size() / 2).norm());
    }
    EXPECT_NEAR(testing::fitted_order(dts, errors), 1.0, 0.3) << solver;
  }
}

TEST(ImplicitEuler, SettlesOnTheNewtonEquilibriumWithLargeSteps) {
  auto s = testing::pinned_test_cloth(0.02, 0.002);
  const Eigen::VectorXd expected = testing::newton_equilibrium(*s);
  const double limit = testing::leapfrog_stability_limit(*s, s->initial_state(0.0));
  for (const char* solver : {"pcg-reduced", "pcg-multigrid", "sparse-direct"}) {
    ImplicitEuler method(*s, euler_options(5.0 * limit, solver));
    const Eigen::VectorXd x = testing::settle(method, *s);
    EXPECT_LT((x - expected).lpNorm<Eigen::Infinity>(), 1e-8) << solver;
  }
}

TEST(ImplicitEuler, StepFarBeyondTheExplicitLimitStaysBounded) {
  auto s = testing::pinned_test_cloth();
  const Eigen::VectorXd y0 = testing::shaken_state(*s);
  const double limit = testing::leapfrog_stability_limit(*s, y0);
  const Eigen::VectorXd y = run(*s, euler_options(20.0 * limit), y0, 1.0);
  EXPECT_LT((y - y0).head(48).lpNorm<Eigen::Infinity>(), 0.1);
}

TEST(ImplicitEuler, FixedAndMovingParticlesFollowTheirPaths) {
  const testing::CirclingCorner corner = testing::circling_corner();
  ImplicitEuler method(*corner.system, euler_options(1e-2));
  testing::expect_fixed_particles_follow(method, corner, 0.3);
  const IntegratorCounters& c = method.counters();
  EXPECT_EQ(c.steps, 30);
  EXPECT_EQ(c.rhs_evals, 30);
  EXPECT_EQ(c.newton_iters, 30);
  EXPECT_GT(c.linear_iters, 30);
  EXPECT_EQ(c.convergence_failures, 0);
}

// solve = converged is backward Euler itself: its step solves z = y_n + h f(t_{n+1}, z) (the
// linearised step does not), and it takes the hard 1/30 s steps of the stiff sheet (100x). It
// stagnated at 69 and 100 Newton iterations until the stage solve used the exact Jacobian near
// the solution (line_search_newton.hpp): with the definite S alone the iterations converged
// linearly and, where the spring damping's turning direction dominated, cycled.
TEST(ImplicitEuler, ConvergedSolveIsBackwardEuler) {
  auto s = testing::swinging_sheet(100.0);
  IntegratorOptions o = converged_options(true);
  ImplicitEuler method(*s, o);
  const Eigen::VectorXd y0 = s->initial_state(0.0);
  method.reset(0.0, y0);
  Eigen::VectorXd y_n = y0;
  for (int k = 0; k < 10; ++k) {
    const double t = method.step(1.0);
    const Eigen::VectorXd& y = method.state();
    Eigen::VectorXd f(y.size());
    s->rhs(t, y, f);
    Eigen::VectorXd residual = y - y_n - (1.0 / 30.0) * f;
    // Fixed particles are snapped onto their path (pins: no residual either way).
    EXPECT_LT(residual.lpNorm<Eigen::Infinity>(), 1e-7) << "step " << k;
    y_n = y;
  }
  EXPECT_EQ(method.counters().convergence_failures, 0);
  EXPECT_GT(method.counters().newton_iters, 10);
}

// A converged step that runs out of Newton iterations says so, and says what stopped it.
TEST(ImplicitEuler, AnUnconvergedStepNamesWhatStoppedIt) {
  auto s = testing::swinging_sheet(100.0);
  IntegratorOptions o = converged_options(false);
  o.max_newton_iters = 1;
  o.max_step_halvings = 0;
  ImplicitEuler method(*s, o);
  method.reset(0.0, s->initial_state(0.0));
  try {
    method.step(1.0);
    ADD_FAILURE() << "one Newton iteration converged a 1/30 s step at 100x the stiffness";
  } catch (const IntegratorFailure& failure) {
    EXPECT_EQ(failure.flag(), "CONV_FAILURE");
    EXPECT_NE(std::string(failure.what()).find("did not converge in 1 Newton iterations"),
              std::string::npos) << failure.what();
    EXPECT_NE(std::string(failure.what()).find("stopped by the iteration limit"), std::string::npos)
        << failure.what();
  }
  EXPECT_EQ(method.counters().convergence_failures, 1);
}

// A converged step whose solve fails is taken again as two halves (max_step_halvings), as
// ARKODE's fixed steps are: with the Newton limit at which the 1/30 s step of the stiff sheet is
// halved exactly once, the result is two converged 1/60 s steps, and the sub-steps are counted.
TEST(ImplicitEuler, AFailedConvergedStepIsTakenAsTwoHalves) {
  auto s = testing::swinging_sheet(100.0);
  IntegratorOptions o = converged_options(true);
  const Eigen::VectorXd y0 = s->initial_state(0.0);
  IntegratorOptions halves = o;
  halves.dt = 1.0 / 60.0;
  halves.max_newton_iters = 200;
  const Eigen::VectorXd two_halves = run(*s, halves, y0, 1.0 / 30.0);
  bool found = false;
  for (int limit = 1; limit <= 60 && !found; ++limit) {
    o.max_newton_iters = limit;
    ImplicitEuler method(*s, o);
    method.reset(0.0, y0);
    try {
      EXPECT_DOUBLE_EQ(method.step(1.0), 1.0 / 30.0);
    } catch (const IntegratorFailure&) {
      continue;  // a half step fails too at this limit
    }
    if (method.counters().step_halvings != 1) continue;
    found = true;
    EXPECT_EQ(method.counters().steps, 2) << "the two halves";
    EXPECT_EQ(method.counters().attempts, 3) << "the failed whole and the two halves";
    const Eigen::VectorXd diff = method.state() - two_halves;
    EXPECT_LT(diff.lpNorm<Eigen::Infinity>(), 1e-6 * two_halves.lpNorm<Eigen::Infinity>())
        << "Newton limit " << limit;
  }
  EXPECT_TRUE(found) << "no Newton limit halved the step exactly once";
}

// A step whose solves keep failing is halved up to max_step_halvings levels, up to 2^30
// attempts inside one step() call: integrator.max_steps bounds the attempts there too, as in
// arkode-dirk (it ran 592875 attempts past max_steps = 1000 and still ended ok).
TEST(ImplicitEuler, HalvedStepsStopAtMaxSteps) {
  // One Newton iteration converges only on sub-steps thousands of times shorter than dt.
  auto s = testing::swinging_sheet(1.0);
  IntegratorOptions o = converged_options(false);
  o.dt = 0.01;
  o.max_newton_iters = 1;
  o.max_step_halvings = 30;
  o.max_steps = 1000;
  ImplicitEuler method(*s, o);
  method.reset(0.0, s->initial_state(0.0));
  try {
    method.step(1.0);
    ADD_FAILURE() << "the step ended after " << method.counters().attempts << " attempts";
  } catch (const IntegratorFailure& failure) {
    EXPECT_EQ(failure.flag(), "max_steps");
    EXPECT_EQ(method.counters().attempts, 1000);
  }
}

}  // namespace
}  // namespace drape
