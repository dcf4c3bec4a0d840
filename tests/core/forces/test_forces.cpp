// Force kernels against finite differences of their energies, and Jacobians against finite
// differences of the forces (forces.hpp).
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <random>

#include "core/forces/forces.hpp"

namespace drape {
namespace {

Vec3 random_vec(std::mt19937& rng, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  return Vec3(u(rng), u(rng), u(rng));
}

// Central differences of a vector function of d, one column per coordinate.
template <class F>
Mat3 fd_jacobian(F&& f, const Vec3& d, double h) {
  Mat3 j;
  for (int k = 0; k < 3; ++k) {
    Vec3 e = Vec3::Zero();
    e[k] = h;
    j.col(k) = (f(d + e) - f(d - e)) / (2 * h);
  }
  return j;
}

TEST(SpringKernel, ForceIsMinusEnergyGradientOnI) {
  std::mt19937 rng(1);
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3 d = random_vec(rng, 0.05);
    const double k = 10.0 + trial, rest = 0.02 + 0.0001 * trial;
    // E depends on d = x_j - x_i, so dE/dx_i = -dE/dd and the force on i is +dE/dd.
    const Mat3 grad = fd_jacobian([&](const Vec3& dd) { return Vec3::Constant(spring_energy(dd, k, rest)); }, d, 1e-7);
    const Vec3 expected = grad.row(0).transpose();
    EXPECT_LT((spring_force(d, k, rest) - expected).norm(), 1e-6 * (1.0 + expected.norm()));
  }
}

TEST(SpringKernel, JacobianMatchesForceDifferences) {
  std::mt19937 rng(2);
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3 d = random_vec(rng, 0.05);
    const double k = 5.0 + trial, rest = 0.03;
    // dF_i/dx_j = dF_i/dd.
    const Mat3 fd = fd_jacobian([&](const Vec3& dd) { return spring_force(dd, k, rest); }, d, 1e-7);
    EXPECT_LT((spring_jacobian(d, k, rest, false) - fd).norm(), 1e-5 * (1.0 + fd.norm()));
  }
}

TEST(SpringKernel, DefiniteJacobianIsPositiveSemiDefiniteWhenCompressed) {
  const Vec3 d(0.01, 0.0, 0.0);  // half its rest length
  const Mat3 j = spring_jacobian(d, 100.0, 0.02, true);
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(j);
  EXPECT_GE(eig.eigenvalues().minCoeff(), 0.0);
  EXPECT_NEAR(eig.eigenvalues().maxCoeff(), 100.0, 1e-12);
  // The exact Jacobian has the negative transverse stiffness k (1 - L0/L) = -100.
  EXPECT_NEAR(Eigen::SelfAdjointEigenSolver<Mat3>(spring_jacobian(d, 100.0, 0.02, false))
                  .eigenvalues()
                  .minCoeff(),
              -100.0, 1e-9);
}

TEST(SpringKernel, ClosedFormOnAnAxis) {
  const Vec3 d(0.0, 0.03, 0.0);
  EXPECT_TRUE(spring_force(d, 50.0, 0.02).isApprox(Vec3(0.0, 0.5, 0.0)));
  EXPECT_DOUBLE_EQ(spring_energy(d, 50.0, 0.02), 0.5 * 50.0 * 0.01 * 0.01);
}

TEST(SpringKernel, DegenerateSpringHasNoForce) {
  EXPECT_TRUE(spring_force(Vec3::Zero(), 10.0, 0.02).isZero());
  EXPECT_TRUE(spring_jacobian(Vec3::Zero(), 10.0, 0.02, false).isZero());
  EXPECT_TRUE(damping_force(Vec3::Zero(), Vec3::Ones(), 1.0).isZero());
}

TEST(DampingKernel, DissipatesAndOpposesRelativeMotionAlongTheSpring) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 100; ++trial) {
    const Vec3 d = random_vec(rng, 0.05), w = random_vec(rng, 1.0);
    const double c = 0.5;
    const Vec3 f = damping_force(d, w, c);
    // Power on the pair: F_i . v_i + (-F_i) . v_j = -F_i . w <= 0.
    EXPECT_LE(-f.dot(w), 1e-15);
    EXPECT_NEAR(-f.dot(w), -c * std::pow(w.dot(d.normalized()), 2), 1e-12);
  }
  // Separating particles (w along d) pull i towards j.
  EXPECT_GT(damping_force(Vec3(1, 0, 0), Vec3(2, 0, 0), 0.1).x(), 0.0);
}

TEST(DampingKernel, JacobiansMatchForceDifferences) {
  std::mt19937 rng(4);
  for (int trial = 0; trial < 100; ++trial) {
    const Vec3 d = random_vec(rng, 0.05), w = random_vec(rng, 1.0);
    const double c = 0.3;
    const Mat3 fd_v = fd_jacobian([&](const Vec3& ww) { return damping_force(d, ww, c); }, w, 1e-6);
    EXPECT_LT((damping_velocity_jacobian(d, c) - fd_v).norm(), 1e-8);
    const Mat3 fd_x = fd_jacobian([&](const Vec3& dd) { return damping_force(dd, w, c); }, d, 1e-8);
    EXPECT_LT((damping_position_jacobian(d, w, c) - fd_x).norm(), 1e-5 * (1.0 + fd_x.norm()));
  }
}

TEST(CollisionKernel, ForceIsMinusEnergyGradient) {
  std::mt19937 rng(5);
  const double k = 2000.0, delta = 0.01;
  const Vec3 normal(0, 0, 1);
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3 d = random_vec(rng, 0.012);
    if (std::abs(d.norm() - delta) < 1e-5) continue;  // the kink at the threshold
    const Mat3 grad = fd_jacobian([&](const Vec3& dd) { return Vec3::Constant(collision_energy(dd, k, delta)); }, d, 1e-8);
    const Vec3 expected = -grad.row(0).transpose();
    EXPECT_LT((collision_force(d, normal, k, delta) - expected).norm(), 1e-5 * (1.0 + expected.norm()));
    const Mat3 fd = fd_jacobian([&](const Vec3& dd) { return collision_force(dd, normal, k, delta); }, d, 1e-8);
    EXPECT_LT((collision_jacobian(d, k, delta, false) - fd).norm(), 1e-4 * (1.0 + fd.norm()));
  }
}

TEST(CollisionKernel, ClosedFormPushesOutToTheThreshold) {
  const Vec3 normal(0, 0, 1);
  // 4 mm from the object particle with a 10 mm threshold: k (delta - d) = 1000 * 0.006.
  const Vec3 f = collision_force(Vec3(0, 0.004, 0), normal, 1000.0, 0.01);
  EXPECT_TRUE(f.isApprox(Vec3(0, 6.0, 0)));
  EXPECT_TRUE(collision_force(Vec3(0, 0.011, 0), normal, 1000.0, 0.01).isZero());
  // Exactly on the object particle: along its normal with the full k delta.
  EXPECT_TRUE(collision_force(Vec3::Zero(), normal, 1000.0, 0.01).isApprox(Vec3(0, 0, 10.0)));
}

}  // namespace
}  // namespace drape
