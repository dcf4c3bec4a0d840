// Choi and Ko's BDF2, linearised and converged: second order, settles on the equilibrium, never
// gains energy at the frame step, restarts as implicit Euler at events, rejects keys it does not
// read; the converged step solves BDF2's equation.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/SparseLU>
#include <map>

#include "integrators/bdf2/bdf2.hpp"
#include "integrators/implicit_euler/implicit_euler.hpp"
#include "integrators/registry/options_reader.hpp"
#include "tests/support/reference_trajectory.hpp"
#include "tests/support/swinging_sheet.hpp"
#include "tests/support/test_support.hpp"

namespace drape {
namespace {

// bdf2 at step dt with its linear systems solved to round-off, linearised about `about`, read
// as a scene's would be.
IntegratorOptions bdf2_options(double dt, const std::string& linear_solver,
                               const std::string& about = "predictor") {
  return read_integrator_options({{"name", "bdf2"},
                                  {"dt", dt},
                                  {"linear_solver", linear_solver},
                                  {"linear_tolerance", 1e-12},
                                  {"max_linear_iters", 1000},
                                  {"linearise_about", about}},
                                 "test", "integrator");
}

// bdf2 with solve = converged at step dt, ARKODE's test at `rtol` (atol = rtol / 1000, the
// defaults' ratio), read as a scene's would be.
IntegratorOptions converged_options(double dt, double rtol) {
  return read_integrator_options({{"name", "bdf2"},
                                  {"dt", dt},
                                  {"solve", "converged"},
                                  {"rtol", rtol},
                                  {"atol", 1e-3 * rtol}},
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
// times: its fitted slope is BDF2's order, linearised about the predictor with each linear
// solver, about y_n, and converged. The step from the predictor is BDF2's own solution to
// within a thousandth of the error (its Newton iteration starts O(h^2) from it, not O(h)).
TEST(Bdf2, TrajectoryIsSecondOrder) {
  auto s = hanging_chain(6, 0.0, 0.0);
  const Eigen::VectorXd y0 = swung_chain(*s);
  const Eigen::VectorXd reference = testing::reference_trajectory(*s, y0, 0.1);
  const Eigen::Index n3 = reference.size() / 2;
  const std::vector<double> dts = {4e-4, 2e-4, 1e-4, 5e-5};
  std::map<std::string, std::vector<double>> errors;
  for (const char* run :
       {"pcg-reduced", "pcg-multigrid", "sparse-direct", "current", "converged"}) {
    const std::string name = run;
    for (const double dt : dts) {
      Bdf2 method(*s, name == "converged" ? converged_options(dt, 1e-10)
                      : name == "current" ? bdf2_options(dt, "pcg-multigrid", "current")
                                          : bdf2_options(dt, run));
      method.reset(0.0, y0);
      errors[name].push_back((testing::run_until(method, 0.1) - reference).head(n3).norm());
    }
    EXPECT_NEAR(testing::fitted_order(dts, errors[name]), 2.0, 0.15) << run;
  }
  for (std::size_t k = 0; k < dts.size(); ++k)
    EXPECT_NEAR(errors["sparse-direct"][k], errors["converged"][k],
                1e-3 * errors["converged"][k])
        << dts[k];
}

// The weighted RMS norm (ARKODE's weights 1 / (rtol |y_n| + atol)) of the Newton correction
// that the residual of y_{n+1} = a + gamma f(t, y_{n+1}) still asks for, with the exact
// Jacobian J and a sparse LU: the error the solve left. The position rows' residual must be
// round-off (returned in `position_residual`): the correction then lives in the velocities,
// (M - gamma D - gamma^2 K) dv = -M r_v, and dx = gamma dv.
double correction_norm(const ClothSystem& s, double t, double gamma, const Eigen::VectorXd& a,
                       const Eigen::VectorXd& y, const Eigen::VectorXd& weights,
                       double& position_residual) {
  const Eigen::Index n3 = y.size() / 2;
  Eigen::VectorXd f(y.size());
  s.rhs(t, y, f);
  Eigen::VectorXd r = y - a - gamma * f;
  for (const int i : s.constraints().fixed_particles()) {  // prescribed, then projected
    r.segment<3>(3 * i).setZero();
    r.segment<3>(n3 + 3 * i).setZero();
  }
  position_residual = r.head(n3).lpNorm<Eigen::Infinity>();
  Eigen::SparseMatrix<double> dfdx, dfdv, identity(n3, n3);
  s.force_jacobians(y.head(n3), y.tail(n3), false, dfdx, dfdv);
  identity.setIdentity();
  const double m = s.particle_mass();
  const Eigen::SparseMatrix<double> a_v = m * identity - gamma * dfdv - gamma * gamma * dfdx;
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(a_v);
  Eigen::VectorXd correction(y.size());
  correction.tail(n3) = lu.solve(Eigen::VectorXd(-m * r.tail(n3)));
  correction.head(n3) = gamma * correction.tail(n3);
  return std::sqrt(correction.cwiseProduct(weights).squaredNorm() / static_cast<double>(y.size()));
}

// The swinging sheet at the frame step: each converged step solves BDF2's equation with equal
// steps, y_{n+1} = 4/3 y_n - 1/3 y_{n-1} + 2/3 h f(y_{n+1}) (the first one backward Euler's,
// y_1 = y_0 + h f(y_1)), to within ARKODE's tolerance 0.1 in its weights at either rtol.
TEST(Bdf2, ConvergedStepSolvesItsEquation) {
  const double h = 1.0 / 30.0;
  for (const double rtol : {1e-4, 1e-8}) {
    auto s = testing::swinging_sheet(1.0);
    Bdf2 method(*s, converged_options(h, rtol));
    std::vector<Eigen::VectorXd> y = {s->initial_state(0.0)};
    method.reset(0.0, y[0]);
    for (int k = 1; k <= 6; ++k) {
      method.step(1.0);
      y.push_back(method.state());
      const bool first = k == 1;
      const Eigen::VectorXd a = first ? y[0] : Eigen::VectorXd((4.0 * y[k - 1] - y[k - 2]) / 3.0);
      const Eigen::VectorXd weights = 1.0 / (rtol * y[k - 1].array().abs() + 1e-3 * rtol);
      double position_residual = 0.0;
      const double error = correction_norm(*s, k * h, first ? h : 2.0 * h / 3.0, a, y[k],
                                           weights, position_residual);
      EXPECT_LT(position_residual, 1e-14) << rtol << " step " << k;
      EXPECT_LT(error, 0.1) << rtol << " step " << k;
      EXPECT_GT((y[k] - y[k - 1]).lpNorm<Eigen::Infinity>(), 1e-3) << "the sheet must move";
    }
    EXPECT_EQ(method.counters().convergence_failures, 0);
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
  for (const char* about : {"predictor", "current"}) {
    std::vector<double> errors;
    for (const double dt : dts) {
      Bdf2 method(*s, bdf2_options(dt, "sparse-direct", about));
      method.reset(0.0, y0);
      for (int k = 1; method.time() < 0.1 - 1e-12; ++k)
        testing::run_until(method, std::min(0.1, 0.0073 * k));
      errors.push_back((method.state() - reference).head(n3).norm());
    }
    EXPECT_NEAR(testing::fitted_order(dts, errors), 2.0, 0.15) << about;
  }
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
      for (const char* about : {"predictor", "current"}) {
        Bdf2 method(*s, bdf2_options(1.0 / 30.0, solver, about));
        const Eigen::VectorXd x = testing::settle(method, *s);
        EXPECT_LT((x - expected).lpNorm<Eigen::Infinity>(), 1e-8)
            << s->num_particles() << " particles, " << solver << ", " << about;
      }
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
  for (const char* about : {"current", "predictor"}) {
    IntegratorOptions o = bdf2_options(1.0 / 30.0, "pcg-multigrid", about);
    Bdf2 method(*s, o);
    method.reset(0.0, y0);
    o = bdf2_options(1.0 / 30.0, "pcg-multigrid");
    o.name = "implicit-euler";
    ImplicitEuler euler(*s, o);
    euler.reset(0.0, y0);
    double highest = -1e300;
    while (method.time() < 3.0 - 1e-12) {
      method.step(3.0);
      euler.step(3.0);
      highest = std::max(highest, energy_of(*s, method.state()));
    }
    EXPECT_LE(highest, start) << about;
    EXPECT_GT(energy_of(*s, method.state()), energy_of(*s, euler.state())) << about;
  }
}

// Five steps of the circling corner, then the event: the pinned corner is released and `method`
// reset on the state it reached, which is returned.
Eigen::VectorXd restart_after_release(Bdf2& method, const testing::CirclingCorner& corner) {
  method.reset(0.0, corner.start);
  for (int k = 0; k < 5; ++k) method.step(1.0);
  corner.system->constraints().release(0);
  const Eigen::VectorXd y = method.state();
  method.reset(method.time(), y);
  return y;
}

// After reset() (an event) the history is gone: the next step is implicit Euler's from that
// state. Linearised about y_n it is implicit-euler's step, bit for bit with the direct solve, to
// CG's tolerance with multigrid CG (whose start projects on each integrator's own last solves).
// With solve = converged it is implicit-euler's converged step (bit for bit: the Newton's CG
// starts from zero).
TEST(Bdf2, RestartsWithAnImplicitEulerStep) {
  std::vector<IntegratorOptions> runs = {bdf2_options(1e-2, "sparse-direct", "current"),
                                         bdf2_options(1e-2, "pcg-multigrid", "current"),
                                         converged_options(1e-2, 1e-6)};
  for (IntegratorOptions& o : runs) {
    const bool exact = o.linear_solver == "sparse-direct" || o.solve == "converged";
    const testing::CirclingCorner corner = testing::circling_corner();
    ClothSystem& s = *corner.system;
    Bdf2 method(s, o);
    const Eigen::VectorXd y = restart_after_release(method, corner);
    const double t = method.time();
    method.step(1.0);
    o.name = "implicit-euler";
    ImplicitEuler euler(s, o);
    euler.reset(t, y);
    euler.step(1.0);
    EXPECT_EQ(method.time(), euler.time());
    if (exact)
      EXPECT_EQ(method.state(), euler.state()) << o.linear_solver << " " << o.solve;
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

// Linearised about the predictor, the restart step is one Newton iteration of implicit Euler's
// equation from the body forces' step (no springs): nearer that equation's solution (converged
// implicit-euler, computed by the line-search Newton) than implicit-euler's one iteration from
// y_n.
TEST(Bdf2, RestartsFromThePredictorNearerImplicitEulersSolution) {
  const testing::CirclingCorner corner = testing::circling_corner();
  ClothSystem& s = *corner.system;
  Bdf2 method(s, bdf2_options(1e-2, "sparse-direct"));
  const Eigen::VectorXd y = restart_after_release(method, corner);
  const double t = method.time();
  method.step(1.0);
  IntegratorOptions linearised = bdf2_options(1e-2, "sparse-direct", "current");
  linearised.name = "implicit-euler";
  IntegratorOptions converged = converged_options(1e-2, 1e-12);
  converged.name = "implicit-euler";
  std::vector<Eigen::VectorXd> ends;
  for (const IntegratorOptions& o : {linearised, converged}) {
    ImplicitEuler euler(s, o);
    euler.reset(t, y);
    euler.step(1.0);
    ends.push_back(euler.state());
  }
  const double from_predictor = (method.state() - ends[1]).lpNorm<Eigen::Infinity>();
  const double from_current = (ends[0] - ends[1]).lpNorm<Eigen::Infinity>();
  EXPECT_LT(from_predictor, from_current);
  EXPECT_EQ(method.counters().resets, 1);
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
  unused["rtol"] = 1e-5;
  EXPECT_EQ(error_of(unused), "scene.json: integrator.rtol: not used by this run of 'bdf2': "
                              "only the arkode-* integrators and, with solve = converged, "
                              "implicit-euler and bdf2 read it");
  nlohmann::json converged = unused;
  converged["solve"] = "converged";
  converged["max_newton_iters"] = 50;
  converged["max_step_halvings"] = 0;
  converged["exact_solve"] = "bicgstab";
  EXPECT_EQ(error_of(converged), "no error");
  EXPECT_TRUE(uses_line_search(read_integrator_options(converged, "scene.json", "integrator")));
  EXPECT_FALSE(uses_line_search(o));
  nlohmann::json bad_solve = plain;
  bad_solve["solve"] = "exact";
  EXPECT_EQ(error_of(bad_solve), "scene.json: integrator.solve: unknown solve 'exact' (one of: "
                                 "linearised, converged)");
  nlohmann::json current = plain;
  current["linearise_about"] = "current";
  EXPECT_EQ(error_of(current), "no error");
  nlohmann::json bad_about = plain;
  bad_about["linearise_about"] = "midpoint";
  EXPECT_EQ(error_of(bad_about), "scene.json: integrator.linearise_about: unknown value "
                                 "'midpoint' (one of predictor, current, default predictor)");
  nlohmann::json bad_solver = plain;
  bad_solver["linear_solver"] = "gmres";
  EXPECT_EQ(error_of(bad_solver).rfind("scene.json: integrator.linear_solver: ", 0), 0u);
}

}  // namespace
}  // namespace drape
