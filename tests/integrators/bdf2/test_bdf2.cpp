// Choi and Ko's linearised BDF2: second order, settles on the equilibrium, never gains energy at
// the frame step, restarts as implicit Euler at events, rejects keys it does not read.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "integrators/bdf2/bdf2.hpp"
#include "integrators/implicit_euler/implicit_euler.hpp"
#include "tests/support/reference_trajectory.hpp"
#include "tests/support/test_support.hpp"

namespace drape {
namespace {

// bdf2 at step dt with its linear systems solved to round-off, read as a scene's would be.
IntegratorOptions bdf2_options(double dt, const std::string& linear_solver) {
  return read_integrator_options({{"name", "bdf2"},
                                  {"dt", dt},
                                  {"linear_solver", linear_solver},
                                  {"linear_tolerance", 1e-12},
                                  {"max_linear_iters", 1000}},
                                 "test", "integrator");
}

// A chain of `length` particles hanging from its pinned top (small_cloth's springs, bending
// included). Every spring stays stretched while it swings, so the definite Jacobian is the
// exact one and the linearisation keeps BDF2's order.
std::unique_ptr<ClothSystem> hanging_chain(int length, double damping_spring,
                                           double damping_air) {
  ClothParams p = testing::small_cloth(length, 1);
  p.damping_spring = damping_spring;
  p.damping_air = damping_air;
  auto s = std::make_unique<ClothSystem>(build_cloth(p), nullptr, ForceParams{});
  s->constraints().fix_at(0, s->cloth().rest_positions.segment<3>(0));
  return s;
}

// The chain's equilibrium turned 0.2 rad about its pin, at rest: it swings and bounces.
Eigen::VectorXd swung_chain(const ClothSystem& s) {
  Eigen::VectorXd y = Eigen::VectorXd::Zero(6 * s.num_particles());
  const Eigen::VectorXd x = testing::newton_equilibrium(s);
  const Vec3 pin = x.segment<3>(0);
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(0.2, Vec3::UnitZ()).toRotationMatrix();
  for (int i = 0; i < s.num_particles(); ++i)
    y.segment<3>(3 * i) = pin + turn * (x.segment<3>(3 * i) - pin);
  return y;
}

double energy_of(const ClothSystem& s, const Eigen::VectorXd& y) {
  const Eigen::Index n3 = y.size() / 2;
  return s.energy(y.head(n3), y.tail(n3)).total();
}

// The position error at t_end = 0.1 s against the exact trajectory, at dt = 4e-4 s halved three
// times: its fitted slope is BDF2's order.
TEST(Bdf2, TrajectoryIsSecondOrder) {
  auto s = hanging_chain(6, 0.0, 0.0);
  const Eigen::VectorXd y0 = swung_chain(*s);
  const Eigen::VectorXd reference = testing::reference_trajectory(*s, y0, 0.1);
  const Eigen::Index n3 = reference.size() / 2;
  for (const char* solver : {"pcg-reduced", "pcg-multigrid", "sparse-direct"}) {
    const std::vector<double> dts = {4e-4, 2e-4, 1e-4, 5e-5};
    std::vector<double> errors;
    for (const double dt : dts) {
      Bdf2 method(*s, bdf2_options(dt, solver));
      method.reset(0.0, y0);
      errors.push_back((testing::run_until(method, 0.1) - reference).head(n3).norm());
    }
    EXPECT_NEAR(testing::fitted_order(dts, errors), 2.0, 0.15) << solver;
  }
}

// Output and event times cut steps short (here every 7.3 ms, off the grid of every dt): the
// variable-step formula keeps the second order, and the slivers never become the history's
// spacing.
TEST(Bdf2, StaysSecondOrderWithStepsCutShortAtStopTimes) {
  auto s = hanging_chain(6, 0.0, 0.0);
  const Eigen::VectorXd y0 = swung_chain(*s);
  const Eigen::VectorXd reference = testing::reference_trajectory(*s, y0, 0.1);
  const Eigen::Index n3 = reference.size() / 2;
  const std::vector<double> dts = {4e-4, 2e-4, 1e-4, 5e-5};
  std::vector<double> errors;
  for (const double dt : dts) {
    Bdf2 method(*s, bdf2_options(dt, "sparse-direct"));
    method.reset(0.0, y0);
    for (int k = 1; method.time() < 0.1 - 1e-12; ++k)
      testing::run_until(method, std::min(0.1, 0.0073 * k));
    errors.push_back((method.state() - reference).head(n3).norm());
  }
  EXPECT_NEAR(testing::fitted_order(dts, errors), 2.0, 0.15);
}

// At a fixed point y_{n+1} = y_n = y_{n-1} the linearised step reads gamma f(y_n) = 0: what a
// damped run settles on is the static equilibrium, at any step.
TEST(Bdf2, SettlesOnTheNewtonEquilibriumAtTheFrameStep) {
  std::vector<std::unique_ptr<ClothSystem>> systems;
  systems.push_back(hanging_chain(8, 0.02, 0.002));
  systems.push_back(testing::pinned_test_cloth(0.02, 0.002));
  for (const auto& s : systems) {
    const Eigen::VectorXd expected = testing::newton_equilibrium(*s);
    for (const char* solver : {"pcg-reduced", "pcg-multigrid", "sparse-direct"}) {
      Bdf2 method(*s, bdf2_options(1.0 / 30.0, solver));
      const Eigen::VectorXd x = testing::settle(method, *s);
      EXPECT_LT((x - expected).lpNorm<Eigen::Infinity>(), 1e-8)
          << s->num_particles() << " particles, " << solver;
    }
  }
}

// An undamped 8 x 8 cloth hanging from one top corner, released at rest: it swings about the
// pin. 3 s at 1/30 s: BDF2 damps the modes it does not resolve and never ends a step above the
// energy it started with, and keeps more of the swing's energy than implicit Euler (Choi and
// Ko's "responsive").
TEST(Bdf2, NeverGainsEnergyOnTheUndampedHangingCloth) {
  auto s = std::make_unique<ClothSystem>(build_cloth(testing::small_cloth(8, 8)), nullptr,
                                         ForceParams{});
  s->constraints().fix_at(0, s->cloth().rest_positions.segment<3>(0));
  const Eigen::VectorXd y0 = s->initial_state(0.0);
  const double start = energy_of(*s, y0);
  IntegratorOptions o = bdf2_options(1.0 / 30.0, "pcg-multigrid");
  Bdf2 method(*s, o);
  method.reset(0.0, y0);
  o.name = "implicit-euler";
  ImplicitEuler euler(*s, o);
  euler.reset(0.0, y0);
  double highest = -1e300;
  while (method.time() < 3.0 - 1e-12) {
    method.step(3.0);
    euler.step(3.0);
    highest = std::max(highest, energy_of(*s, method.state()));
  }
  EXPECT_LE(highest, start);
  EXPECT_GT(energy_of(*s, method.state()), energy_of(*s, euler.state()));
}

// After reset() (an event) the history is gone: the next step is implicit Euler's from that
// state, bit for bit with the direct solve, to CG's tolerance with multigrid CG (whose start
// projects on each integrator's own last solves).
TEST(Bdf2, RestartsWithAnImplicitEulerStep) {
  for (const char* solver : {"sparse-direct", "pcg-multigrid"}) {
    const testing::CirclingCorner corner = testing::circling_corner();
    ClothSystem& s = *corner.system;
    IntegratorOptions o = bdf2_options(1e-2, solver);
    Bdf2 method(s, o);
    method.reset(0.0, corner.start);
    for (int k = 0; k < 5; ++k) method.step(1.0);
    // The event: the pinned corner is released.
    s.constraints().release(0);
    const double t = method.time();
    const Eigen::VectorXd y = method.state();
    method.reset(t, y);
    method.step(1.0);
    o.name = "implicit-euler";
    ImplicitEuler euler(s, o);
    euler.reset(t, y);
    euler.step(1.0);
    EXPECT_EQ(method.time(), euler.time());
    if (std::string(solver) == "sparse-direct")
      EXPECT_EQ(method.state(), euler.state());
    else
      EXPECT_LT((method.state() - euler.state()).lpNorm<Eigen::Infinity>(),
                1e-10 * (euler.state() - y).lpNorm<Eigen::Infinity>());
    // The step after it is BDF2's again: it differs from implicit Euler's.
    method.step(1.0);
    euler.step(1.0);
    EXPECT_GT((method.state() - euler.state()).lpNorm<Eigen::Infinity>(), 1e-6);
    EXPECT_EQ(method.counters().resets, 1);
  }
}

std::string error_of(const nlohmann::json& options) {
  return testing::input_error_message(
      [&] { read_integrator_options(options, "scene.json", "integrator"); });
}

TEST(Bdf2, ReadsTheLinearSolverKeysAndRejectsOthers) {
  const nlohmann::json plain = {{"name", "bdf2"}, {"dt", 0.01}};
  const IntegratorOptions o = read_integrator_options(plain, "scene.json", "integrator");
  EXPECT_EQ(linear_solver_of(o), "pcg-multigrid");
  EXPECT_EQ(linear_tolerance_of(o), 1e-3);
  nlohmann::json tuned = plain;
  tuned["linear_solver"] = "sparse-direct";
  tuned["linear_tolerance"] = 1e-6;
  tuned["max_linear_iters"] = 50;
  EXPECT_EQ(error_of(tuned), "no error");
  nlohmann::json unknown = plain;
  unknown["iterations"] = 3;
  EXPECT_EQ(error_of(unknown), "scene.json: integrator.iterations: unknown key");
  nlohmann::json unused = plain;
  unused["solve"] = "converged";
  EXPECT_EQ(error_of(unused), "scene.json: integrator.solve: not used by this run of 'bdf2': "
                              "only implicit-euler read it");
  nlohmann::json bad_solver = plain;
  bad_solver["linear_solver"] = "gmres";
  EXPECT_EQ(error_of(bad_solver).rfind("scene.json: integrator.linear_solver: ", 0), 0u);
}

}  // namespace
}  // namespace drape
