// Leap-frog and symplectic Euler: orders of accuracy, energy behaviour, synchronised output.
#include <gtest/gtest.h>

#include "integrators/explicit/leapfrog.hpp"
#include "integrators/explicit/symplectic_euler.hpp"
#include "tests/support/test_support.hpp"

namespace drape {
namespace {

template <class Method>
Eigen::VectorXd solve(ClothSystem& s, const Eigen::VectorXd& y0, double dt, double t_end) {
  Method method(s, dt);
  method.reset(0.0, y0);
  return testing::run_until(method, t_end);
}

template <class Method>
double trajectory_order(double dt0) {
  auto s = testing::pinned_test_cloth();
  const Eigen::VectorXd y0 = testing::shaken_state(*s);
  const double t_end = 0.1;
  const Eigen::VectorXd reference = solve<Leapfrog>(*s, y0, dt0 / 256, t_end);
  std::vector<double> dts, errors;
  for (int k = 0; k < 4; ++k) {
    const double dt = dt0 / (1 << k);
    const Eigen::VectorXd y = solve<Method>(*s, y0, dt, t_end);
    dts.push_back(dt);
    errors.push_back((y.head(y.size() / 2) - reference.head(y.size() / 2)).norm());
  }
  return testing::fitted_order(dts, errors);
}

TEST(Leapfrog, TrajectoryIsSecondOrder) { EXPECT_NEAR(trajectory_order<Leapfrog>(1e-3), 2.0, 0.3); }

TEST(SymplecticEuler, TrajectoryIsFirstOrder) {
  EXPECT_NEAR(trajectory_order<SymplecticEuler>(5e-4), 1.0, 0.3);
}

double energy_total(const ClothSystem& s, const Eigen::VectorXd& y) {
  const Eigen::Index n3 = y.size() / 2;
  return s.energy(ConstVecMap(y.data(), n3), ConstVecMap(y.data() + n3, n3)).total();
}

// Largest |E(t) - E(0)| over [0, t_end], with E from synchronised velocities.
double max_energy_error(ClothSystem& s, const Eigen::VectorXd& y0, double dt, double t_end) {
  Leapfrog method(s, dt);
  method.reset(0.0, y0);
  const double e0 = energy_total(s, y0);
  double worst = 0.0;
  while (method.time() < t_end - 1e-12) {
    method.step(t_end);
    worst = std::max(worst, std::abs(energy_total(s, method.state()) - e0));
  }
  return worst;
}

TEST(Leapfrog, EnergyErrorIsSecondOrder) {
  auto s = testing::pinned_test_cloth();
  const Eigen::VectorXd y0 = testing::shaken_state(*s);
  std::vector<double> dts, errors;
  for (int k = 0; k < 4; ++k) {
    dts.push_back(1e-3 / (1 << k));
    errors.push_back(max_energy_error(*s, y0, dts.back(), 0.2));
  }
  EXPECT_NEAR(testing::fitted_order(dts, errors), 2.0, 0.3);
}

TEST(Leapfrog, NoSecularEnergyDriftOverALongRun) {
  auto s = testing::pinned_test_cloth();
  const Eigen::VectorXd y0 = testing::shaken_state(*s);
  const double dt = 1e-3, t_end = 40.0;
  Leapfrog method(*s, dt);
  method.reset(0.0, y0);
  const double e0 = energy_total(*s, y0);
  // Energy error in the first and the last quarter of the run, and its linear trend.
  double first = 0.0, last = 0.0, st = 0, se = 0, stt = 0, ste = 0;
  long n = 0;
  while (method.time() < t_end - 1e-12) {
    const double t = method.step(t_end);
    const double err = energy_total(*s, method.state()) - e0;
    if (t < t_end / 4) first = std::max(first, std::abs(err));
    if (t > 3 * t_end / 4) last = std::max(last, std::abs(err));
    st += t, se += err, stt += t * t, ste += t * err, ++n;
  }
  const double slope = (n * ste - st * se) / (n * stt - st * st);
  EXPECT_GT(first, 0.0);
  EXPECT_LT(last, 2.0 * first) << "the error band does not widen";
  EXPECT_LT(std::abs(slope) * t_end, 0.1 * first) << "no trend over the run";
  EXPECT_LT(first, 1e-3 * std::abs(e0));
}

TEST(Leapfrog, FixedParticlesStayPut) {
  auto s = testing::pinned_test_cloth(0.01, 0.001);
  const Eigen::VectorXd y0 = testing::shaken_state(*s);
  const Eigen::VectorXd y = solve<Leapfrog>(*s, y0, 1e-3, 0.5);
  EXPECT_EQ(y.segment<3>(0), y0.segment<3>(0));
  EXPECT_EQ(y.segment<3>(9), y0.segment<3>(9));
  EXPECT_TRUE(y.segment<3>(48).isZero());
}

TEST(Leapfrog, LandsExactlyOnTheStopTime) {
  auto s = testing::pinned_test_cloth();
  Leapfrog method(*s, 1.0 / 30.0);
  method.reset(0.0, s->initial_state(0.0));
  // One step of 1/30 s per call, the last one shortened to land on 0.05.
  EXPECT_DOUBLE_EQ(method.step(0.05), 1.0 / 30.0);
  EXPECT_DOUBLE_EQ(method.step(0.05), 0.05);
  EXPECT_EQ(method.counters().steps, 2);
}

}  // namespace
}  // namespace drape
