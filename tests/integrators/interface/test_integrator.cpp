// The interface every integrator shares: fixed steps that land on t_stop, the bookkeeping of an
// accepted step and of restarts, the max_steps bound on attempts, the counters' JSON names
// (docs/outputs.md, summary.json `counters`).
#include "integrators/interface/integrator.hpp"

#include <gtest/gtest.h>

#include "tests/support/test_support.hpp"

namespace drape {
namespace {

/// The plainest integrator: fixed steps of dt that change nothing but the time, with the
/// attempts bounded as the fixed-step integrators bound them.
class Clock final : public Integrator {
 public:
  Clock(ClothSystem& system, double dt, long max_steps)
      : Integrator(system), m_dt(dt), m_max_steps(max_steps) {}
  double step(double t_stop) override {
    check_attempts(m_max_steps);
    return accept_fixed_step(fixed_step_end(m_dt, m_t, t_stop));
  }

 private:
  double m_dt;
  long m_max_steps;
};

TEST(Integrator, FixedStepsLandOnTheStopTime) {
  EXPECT_EQ(fixed_step_end(0.1, 0.0, 1.0), 0.1);
  EXPECT_EQ(fixed_step_end(0.1, 0.95, 1.0), 1.0) << "a shorter last step";
  EXPECT_EQ(fixed_step_end(0.1, 0.9, 1.0), 1.0) << "a remainder of dt within round-off";
  EXPECT_EQ(fixed_step_end(0.1, 0.9 - 1e-6, 1.0), 0.9 - 1e-6 + 0.1);
  // dt = 1/30 over 1 s: 30 steps, the last exactly at 1 s, not 30 and a sliver.
  ClothSystem system(build_cloth(testing::small_cloth(2, 2)), nullptr, ForceParams{});
  Clock clock(system, 1.0 / 30.0, 1000);
  clock.reset(0.0, system.initial_state(0.0));
  while (clock.time() < 1.0) clock.step(1.0);
  EXPECT_EQ(clock.time(), 1.0);
  EXPECT_EQ(clock.counters().steps, 30);
  EXPECT_EQ(clock.counters().attempts, 30);
  EXPECT_NEAR(clock.last_step(), 1.0 / 30.0, 1e-12);
}

TEST(Integrator, EveryResetAfterTheFirstIsARestart) {
  ClothSystem system(build_cloth(testing::small_cloth(2, 2)), nullptr, ForceParams{});
  Clock clock(system, 0.01, 1000);
  const Eigen::VectorXd y = testing::jitter(system.initial_state(0.0), 0.1, 3);
  clock.reset(0.5, y);
  EXPECT_EQ(clock.time(), 0.5);
  EXPECT_EQ(clock.state(), y);
  EXPECT_EQ(clock.counters().resets, 0) << "the start is no restart";
  clock.step(1.0);
  clock.reset(clock.time(), y);
  clock.reset(clock.time(), y);
  EXPECT_EQ(clock.counters().resets, 2);
  EXPECT_EQ(clock.counters().steps, 1) << "a reset takes no step";
}

TEST(Integrator, AttemptsStopAtMaxSteps) {
  ClothSystem system(build_cloth(testing::small_cloth(2, 2)), nullptr, ForceParams{});
  Clock clock(system, 0.01, 3);
  clock.reset(0.0, system.initial_state(0.0));
  for (int k = 0; k < 3; ++k) clock.step(1.0);
  try {
    clock.step(1.0);
    FAIL() << "no error";
  } catch (const IntegratorFailure& e) {
    EXPECT_EQ(e.flag(), "max_steps");
    EXPECT_EQ(std::string(e.what()),
              "reached integrator.max_steps = 3 step attempts at t = " + std::to_string(0.03));
  }
  EXPECT_EQ(clock.counters().attempts, 3);
}

TEST(Integrator, CountersKeepTheirJsonNames) {
  IntegratorCounters c;
  c.steps = 1;
  c.attempts = 2;
  c.rhs_evals = 3;
  c.newton_iters = 4;
  c.linear_iters = 5;
  c.jacobian_setups = 6;
  c.error_test_failures = 7;
  c.convergence_failures = 8;
  c.resets = 9;
  c.step_halvings = 10;
  c.line_search_backtracks = 11;
  c.potential_decrease = 12.5;
  c.potential_rises = 13;
  EXPECT_EQ(c.to_json(), nlohmann::json::parse(R"({"steps": 1, "attempts": 2, "rhs_evals": 3,
      "newton_iters": 4, "linear_iters": 5, "jacobian_setups": 6, "error_test_failures": 7,
      "convergence_failures": 8, "resets": 9, "step_halvings": 10, "line_search_backtracks": 11,
      "potential_decrease": 12.5, "potential_rises": 13})"));
}

// A step's decrease adds up; a rise counts only above the round-off of E's terms (1e3 epsilon
// of their magnitude).
TEST(Integrator, PotentialChangesAddUpAndRisesCountAboveRoundOff) {
  IntegratorCounters c;
  c.add_potential_change(3.0, 1.0, 5.0);
  EXPECT_EQ(c.potential_decrease, 2.0);
  EXPECT_EQ(c.potential_rises, 0);
  c.add_potential_change(1.0, 1.0 + 1e-14, 10.0);  // below 1e3 * 2.2e-16 * 10 = 2.2e-12
  EXPECT_EQ(c.potential_rises, 0);
  c.add_potential_change(1.0, 1.0 + 1e-11, 10.0);
  EXPECT_EQ(c.potential_rises, 1);
  EXPECT_NEAR(c.potential_decrease, 2.0 - 1e-14 - 1e-11, 1e-15);
}

}  // namespace
}  // namespace drape
