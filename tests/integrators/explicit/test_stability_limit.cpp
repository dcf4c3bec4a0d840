// The stability limit of the explicit steps with spring damping (docs/model.md, "Stability
// limit"): the linear recursion of symplectic Euler (and of leap-frog, whose positions follow
// it once its damping reuses the stored acceleration, model.md section 6) against the closed
// form h^2 omega^2 + 2 h c < 4, and the integrators themselves just below and just above it.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>

#include "integrators/explicit/leapfrog.hpp"
#include "integrators/explicit/stability_limit.hpp"
#include "integrators/explicit/symplectic_euler.hpp"
#include "tests/support/test_support.hpp"

namespace drape {
namespace {

// A 5 x 5 cloth of structural springs only, at rest, top row pinned, no gravity: its rest state
// is an equilibrium, and with one spring constant k at rest length the damping Jacobian is
// (c_s / k) times the stiffness one, so every mode of omega has the damping rate
// c = (c_s / k) omega^2.
constexpr double c_spring = 0.05;
std::unique_ptr<ClothSystem> resting_cloth(double mass_factor = 1.0) {
  ClothParams p = testing::small_cloth(5, 5);
  p.particle_mass *= mass_factor;
  p.k_shear = 0.0;
  p.k_bending = 0.0;
  p.damping_spring = c_spring;
  ForceParams forces;
  forces.gravity = Vec3::Zero();
  auto s = std::make_unique<ClothSystem>(build_cloth(p), nullptr, forces);
  for (int c = 0; c < p.cols; ++c)
    s->constraints().fix_at(c, s->cloth().rest_positions.segment<3>(3 * c));
  return s;
}

// M^-1 dF/dx and M^-1 dF/dv at rest on the free coordinates.
struct LinearModel {
  Eigen::MatrixXd a, c;
};
LinearModel linearise(const ClothSystem& s) {
  const Eigen::VectorXd y = s.initial_state(0.0);
  const Eigen::Index n3 = y.size() / 2;
  Eigen::SparseMatrix<double> dfdx, dfdv;
  s.force_jacobians(ConstVecMap(y.data(), n3), ConstVecMap(y.data() + n3, n3), false, dfdx, dfdv);
  std::vector<Eigen::Index> free;
  for (Eigen::Index k = 0; k < n3; ++k)
    if (!s.constraints().is_fixed(static_cast<int>(k / 3))) free.push_back(k);
  const auto n = static_cast<Eigen::Index>(free.size());
  const Eigen::MatrixXd x = Eigen::MatrixXd(dfdx), v = Eigen::MatrixXd(dfdv);
  LinearModel m{Eigen::MatrixXd(n, n), Eigen::MatrixXd(n, n)};
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j) {
      m.a(i, j) = x(free[i], free[j]) / s.particle_mass();
      m.c(i, j) = v(free[i], free[j]) / s.particle_mass();
    }
  return m;
}

// Spectral radius of one symplectic Euler step of the linear model: v+ = v + h (A x + C v),
// x+ = x + h v+.
double step_radius(const LinearModel& m, double h) {
  const Eigen::Index n = m.a.rows();
  const Eigen::MatrixXd id = Eigen::MatrixXd::Identity(n, n);
  Eigen::MatrixXd g(2 * n, 2 * n);
  g << id + h * h * m.a, h * (id + h * m.c), h * m.a, id + h * m.c;
  return Eigen::EigenSolver<Eigen::MatrixXd>(g, false).eigenvalues().cwiseAbs().maxCoeff();
}

// The energy after `steps` steps of `dt` from rest with every free particle displaced by up to
// 1e-7 m, relative to the start (the linear regime: the spring energy is 0 at rest).
template <class Method>
double energy_gain(ClothSystem& s, double dt, int steps) {
  Eigen::VectorXd y = s.initial_state(0.0);
  const Eigen::Index n3 = y.size() / 2;
  y.head(n3) = testing::jitter(y.head(n3), 1e-7, 7);
  s.constraints().project(0.0, VecMap(y.data(), n3), VecMap(y.data() + n3, n3));
  const auto energy = [&](const Eigen::VectorXd& state) {
    return s.energy(ConstVecMap(state.data(), n3), ConstVecMap(state.data() + n3, n3)).total();
  };
  Method method(s, dt);
  method.reset(0.0, y);
  const double e0 = energy(y);
  for (int k = 0; k < steps; ++k) method.step(1e9);
  return energy(method.state()) / e0;
}

TEST(StabilityLimit, TheDampedRecursionMatchesTheClosedForm) {
  const auto s = resting_cloth();
  const LinearModel m = linearise(*s);
  const double omega2 = (-m.a).eval().selfadjointView<Eigen::Lower>().eigenvalues().maxCoeff();
  const double alpha = c_spring / s->cloth().params.k_structural;  // c = alpha omega^2
  // h^2 omega^2 + 2 h alpha omega^2 < 4: h < sqrt(alpha^2 + 4 / omega^2) - alpha.
  const double closed_form = std::sqrt(alpha * alpha + 4.0 / omega2) - alpha;
  // Damping that matters: the limit is well below the undamped 2 / omega.
  EXPECT_LT(closed_form, 0.9 * 2.0 / std::sqrt(omega2));
  // The premise: C = alpha A on the free coordinates.
  EXPECT_LT((m.c - alpha * m.a).cwiseAbs().maxCoeff(), 1e-12 * (alpha * m.a).cwiseAbs().maxCoeff());
  // The step's spectral radius crosses 1 there. Modes without stiffness keep eigenvalue 1 (the
  // pinned strings have no transverse stiffness at rest), a defective one that the eigensolver
  // returns to about 1e-8; the fastest mode's eigenvalue passes -1 at a rate of order 1 in
  // h / limit, so 0.1 % on either side is far outside that.
  EXPECT_LE(step_radius(m, 0.999 * closed_form), 1.0 + 1e-6);
  EXPECT_GT(step_radius(m, 1.001 * closed_form), 1.0 + 1e-4);
}

TEST(StabilityLimit, LeapfrogAndSymplecticEulerDecayBelowAndGrowAbove) {
  const auto s = resting_cloth();
  const LinearModel m = linearise(*s);
  const double omega2 = (-m.a).eval().selfadjointView<Eigen::Lower>().eigenvalues().maxCoeff();
  const double alpha = c_spring / s->cloth().params.k_structural;
  const double limit = std::sqrt(alpha * alpha + 4.0 / omega2) - alpha;
  // Enough steps for the fastest mode to grow 1e6 in amplitude at 1.02 times the limit.
  const int steps = static_cast<int>(std::log(1e6) / std::log(step_radius(m, 1.02 * limit))) + 1;
  ASSERT_LT(steps, 20000);
  EXPECT_LT(energy_gain<SymplecticEuler>(*s, 0.98 * limit, steps), 1.0);
  EXPECT_GT(energy_gain<SymplecticEuler>(*s, 1.02 * limit, steps), 1e6);
  EXPECT_LT(energy_gain<Leapfrog>(*s, 0.98 * limit, steps), 1.0);
  EXPECT_GT(energy_gain<Leapfrog>(*s, 1.02 * limit, steps), 1e6);
}

TEST(StabilityLimit, TheEigensolverFindsTheFastestModeAndItsBound) {
  const auto s = resting_cloth();
  const LinearModel m = linearise(*s);
  const double omega2 = (-m.a).eval().selfadjointView<Eigen::Lower>().eigenvalues().maxCoeff();
  const double alpha = c_spring / s->cloth().params.k_structural;
  const Eigen::VectorXd y = s->initial_state(0.0);
  const Eigen::Index n3 = y.size() / 2;
  const ExplicitStabilityLimit limit = explicit_stability_limit(*s, y.head(n3), y.tail(n3));
  // Arnoldi stops at a relative residual of 1e-10: the eigenvalue is then exact to about 1e-10
  // (a symmetric matrix's error is of the residual's square over the gap, at most the residual).
  EXPECT_NEAR(limit.omega * limit.omega, omega2, 1e-9 * omega2);
  EXPECT_NEAR(limit.damping_rate, alpha * omega2, 1e-8 * alpha * omega2);  // c = alpha omega^2
  EXPECT_NEAR(limit.undamped, 2.0 / std::sqrt(omega2), 1e-9 * limit.undamped);
  EXPECT_NEAR(limit.damped, std::sqrt(alpha * alpha + 4.0 / omega2) - alpha, 1e-8 * limit.damped);
  // The progress callback sees every product, counted from 1, and does not change the answer.
  std::vector<long> counts;
  const ExplicitStabilityLimit watched = explicit_stability_limit(
      *s, y.head(n3), y.tail(n3), 1000, [&](long products) { counts.push_back(products); });
  ASSERT_EQ(counts.size(), static_cast<std::size_t>(limit.jacobian_products));
  for (std::size_t k = 0; k < counts.size(); ++k) EXPECT_EQ(counts[k], static_cast<long>(k) + 1);
  EXPECT_EQ(watched.omega, limit.omega);
}

// The eigenvalues of -M^-1 dF/dx are those of -dF/dx over the one particle mass: a cloth of
// 1e-300 kg particles has omega^2 1e300 times larger and its damping rate too, and the limit is
// found (Arnoldi at the forces' scale), where dividing by the mass inside the product overflowed
// the Krylov vectors' norms and failed the Schur decomposition.
TEST(StabilityLimit, ATinyParticleMassScalesTheModesInsteadOfOverflowing) {
  const auto s = resting_cloth();
  const Eigen::VectorXd y = s->initial_state(0.0);
  const Eigen::Index n3 = y.size() / 2;
  const ExplicitStabilityLimit limit = explicit_stability_limit(*s, y.head(n3), y.tail(n3));
  constexpr double factor = 1e-300;
  const auto light = resting_cloth(factor);
  const ExplicitStabilityLimit scaled = explicit_stability_limit(*light, y.head(n3), y.tail(n3));
  EXPECT_NEAR(scaled.omega, limit.omega / std::sqrt(factor), 1e-9 * scaled.omega);
  EXPECT_NEAR(scaled.damping_rate, limit.damping_rate / factor, 1e-8 * scaled.damping_rate);
  // The damped bound is the positive root of h^2 omega^2 + 2 h c = 4; here the damping's term
  // dominates (c scales as 1 / m, omega as 1 / sqrt(m)), so h is about 2 / c, and c^2 is beyond
  // the doubles' range.
  const double h = scaled.damped;
  EXPECT_NEAR(h * h * scaled.omega * scaled.omega + 2.0 * h * scaled.damping_rate, 4.0, 1e-12);
  EXPECT_NEAR(h, 2.0 / scaled.damping_rate, 1e-6 * h);
}

}  // namespace
}  // namespace drape
