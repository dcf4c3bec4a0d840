// Coulomb friction against the object (docs/model.md section 4.12): the mollifier's
// derivatives, the lagged potential's gradient (the friction force) and Hessian against central
// finite differences in both regimes (sticking |u| < epsilon_v h and sliding), the Hessian's
// semi-definiteness and closed-form eigenvalues, the smooth Coulomb force's velocity Jacobian,
// and the velocity-level Coulomb bound.
#include "core/collision/friction.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <random>

#include "core/collision/collision.hpp"
#include "core/dummy/dummy_sources.hpp"

namespace drape {
namespace {

TEST(FrictionMollifier, DerivativesMatchFiniteDifferencesAndJoinTheCoulombLawAtEpsilon) {
  const double eps = 2e-4, d = 1e-10;
  for (const double y : {1e-6, 5e-5, 1e-4, 1.9e-4, 3e-4, 1e-2}) {
    EXPECT_NEAR(friction_f1(y, eps), (friction_f0(y + d, eps) - friction_f0(y - d, eps)) / (2 * d),
                1e-6)
        << y;
    EXPECT_NEAR(friction_f1_slope(y, eps),
                (friction_f1(y + d, eps) - friction_f1(y - d, eps)) / (2 * d), 1e-6 / eps)
        << y;
    EXPECT_DOUBLE_EQ(friction_f1_over_y(y, eps), friction_f1(y, eps) / y) << y;
  }
  // C2 at eps from below: f0(eps - d) = eps - d + O(d^3) (value eps, slope 1, curvature 0), and
  // f1 in [0, 1] rising from 0.
  EXPECT_NEAR(friction_f0(eps * (1 - 1e-4), eps), eps * (1 - 1e-4), 1e-11 * eps);
  EXPECT_DOUBLE_EQ(friction_f0(eps, eps), eps);
  EXPECT_NEAR(friction_f1(eps * (1 - 1e-9), eps), 1.0, 1e-15);
  EXPECT_EQ(friction_f1(0.0, eps), 0.0);
  EXPECT_DOUBLE_EQ(friction_f1_over_y(0.0, eps), 2.0 / eps);
}

// A sphere with the smooth model; particles within the threshold of its surface, where the
// contact force gives each a normal force and a tangent plane at the step's start.
struct FrozenFriction {
  FrozenFriction()
      : dummy(std::make_shared<const Dummy>(make_dummy(
            nlohmann::json{{"builtin", "sphere"}, {"radius", 0.2}}, "test", "dummy", "."))),
        collision(dummy, CollisionParams{0.01, 1000.0, CollisionModel::smooth}, count),
        friction(mu, epsilon),
        start(3 * count) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int i = 0; i < count; ++i) {
      const Vec3 direction = Vec3(u(rng), 0.8 + 0.2 * u(rng), u(rng)).normalized();
      start.segment<3>(3 * i) = (0.2 + 0.004 * (1.0 + u(rng))) * direction;
    }
    friction.freeze(collision, start, h);
  }
  static constexpr int count = 8;
  static constexpr double mu = 0.4, epsilon = 1e-3, h = 0.01;
  std::shared_ptr<const Dummy> dummy;
  Collision collision;
  LaggedFriction friction;
  Eigen::VectorXd start;
};

TEST(LaggedFriction, NormalForceAndBasisAreTheContactsAtTheStart) {
  FrozenFriction f;
  for (int i = 0; i < f.count; ++i) {
    const Vec3 x0 = f.start.segment<3>(3 * i);
    const Vec3 contact = f.collision.force(i, x0);
    ASSERT_GT(contact.norm(), 0.0) << i;
    EXPECT_DOUBLE_EQ(f.friction.normal_force(i), contact.norm());
    // At the start u = 0: D = mu lambda eps / 3, no force, and a normal move costs nothing.
    EXPECT_NEAR(f.friction.energy(i, x0), f.mu * contact.norm() * f.epsilon * f.h / 3.0, 1e-15);
    EXPECT_EQ(f.friction.force(i, x0).norm(), 0.0);
    EXPECT_DOUBLE_EQ(f.friction.energy(i, x0 + 0.003 * contact.normalized()),
                     f.friction.energy(i, x0));
  }
}

TEST(LaggedFriction, ForceIsMinusTheGradientAndHessianItsDerivative) {
  FrozenFriction f;
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double eps = f.epsilon * f.h;
  for (int i = 0; i < f.count; ++i) {
    const Vec3 x0 = f.start.segment<3>(3 * i);
    // Moves within the sticking zone (|u| < eps) and beyond it, in every direction.
    for (const double size : {0.3 * eps, 0.8 * eps, 3.0 * eps, 50.0 * eps}) {
      const Vec3 x = x0 + size * Vec3(u(rng), u(rng), u(rng)).normalized();
      const double d = 1e-4 * eps;
      Vec3 gradient;
      Mat3 fd_hessian;
      for (int a = 0; a < 3; ++a) {
        const Vec3 step = d * Vec3::Unit(a);
        gradient[a] = (f.friction.energy(i, x + step) - f.friction.energy(i, x - step)) / (2 * d);
        fd_hessian.col(a) = -(f.friction.force(i, x + step) - f.friction.force(i, x - step)) / (2 * d);
      }
      const Vec3 force = f.friction.force(i, x);
      EXPECT_LT((force + gradient).norm(), 1e-6 * force.norm()) << i << " " << size;
      const Mat3 hessian = f.friction.hessian(i, x);
      EXPECT_LT((hessian - fd_hessian).norm(), 1e-6 * hessian.norm()) << i << " " << size;
      // The friction force never exceeds Coulomb's mu lambda.
      EXPECT_LE(force.norm(), f.mu * f.friction.normal_force(i) * (1 + 1e-12));
    }
  }
}

TEST(LaggedFriction, HessianIsSemiDefiniteWithTheClosedFormEigenvalues) {
  FrozenFriction f;
  const double eps = f.epsilon * f.h;
  const int i = 3;
  const Vec3 x0 = f.start.segment<3>(3 * i);
  const Vec3 normal = f.collision.force(i, x0).normalized();
  const Vec3 tangent = normal.cross(Vec3::UnitY()).normalized();
  const double scale = f.mu * f.friction.normal_force(i);
  for (const double y : {0.0, 0.25 * eps, 0.9 * eps, 2.0 * eps}) {
    Eigen::SelfAdjointEigenSolver<Mat3> eig(f.friction.hessian(i, x0 + y * tangent));
    // Ascending: 0 along the normal, then mu lambda f1' (along u) and mu lambda f1 / y (across).
    Eigen::Vector3d expected(0.0, scale * friction_f1_slope(y, eps),
                             scale * friction_f1_over_y(y, eps));
    std::sort(expected.data(), expected.data() + 3);
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(eig.eigenvalues()[k], expected[k], 1e-9 * expected[2]) << y << " " << k;
  }
}

// The regularised Coulomb force of an ODE's right-hand side: its velocity Jacobian against
// central differences in v, within the mollifier (|v_t| < epsilon_v) and beyond it, where it is
// Coulomb's mu lambda against v_t; nothing along the normal.
TEST(SmoothCoulombForce, VelocityJacobianMatchesFiniteDifferencesAndBeyondEpsilonIsCoulomb) {
  const double mu = 0.4, epsilon_v = 1e-3;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 8; ++trial) {
    const Vec3 contact = (0.01 + 0.005 * u(rng)) * Vec3(u(rng), 1.0, u(rng)).normalized();
    const double lambda = contact.norm();
    const Vec3 normal = contact / lambda;
    for (const double speed : {0.0, 0.3 * epsilon_v, 0.8 * epsilon_v, 3.0 * epsilon_v,
                               50.0 * epsilon_v}) {
      const Vec3 direction = Vec3(u(rng), u(rng), u(rng)).normalized();
      const Vec3 tangent = (direction - direction.dot(normal) * normal).normalized();
      const Vec3 v = speed * tangent + 0.2 * u(rng) * normal;
      // At v_t = 0 the force's second-order term -mu lambda |v_t| v_t / epsilon_v^2 has zero
      // derivative but central differences of size d see d / epsilon_v of it: a smaller step.
      const double d = (speed == 0.0 ? 1e-7 : 1e-4) * epsilon_v;
      Mat3 fd;
      for (int a = 0; a < 3; ++a) {
        const Vec3 step = d * Vec3::Unit(a);
        fd.col(a) = (smooth_coulomb_force(contact, v + step, mu, epsilon_v) -
                     smooth_coulomb_force(contact, v - step, mu, epsilon_v)) / (2 * d);
      }
      const Mat3 jacobian = smooth_coulomb_velocity_jacobian(contact, v, mu, epsilon_v);
      EXPECT_LT((jacobian - fd).norm(), 1e-6 * jacobian.norm()) << trial << " " << speed;
      EXPECT_LT((jacobian * normal).norm(), 1e-12 * jacobian.norm());
      const Vec3 force = smooth_coulomb_force(contact, v, mu, epsilon_v);
      EXPECT_NEAR(force.dot(normal), 0.0, 1e-15);
      EXPECT_NEAR(force.norm(), mu * lambda * friction_f1(speed, epsilon_v), 1e-12 * mu * lambda);
      if (speed > 0.0) {
        EXPECT_NEAR(force.dot(tangent), -force.norm(), 1e-15) << "against v_t";
      }
    }
  }
  EXPECT_EQ(smooth_coulomb_force(Vec3::Zero(), Vec3(1.0, 2.0, 3.0), mu, epsilon_v), Vec3::Zero());
}

TEST(CoulombVelocityFriction, ShrinksTheTangentialPartByMuTimesTheNormalChange) {
  const Vec3 normal = Vec3(1.0, 2.0, 2.0) / 3.0;
  const Vec3 tangential = Vec3(2.0, -2.0, 1.0);  // |.| = 3, perpendicular to the normal
  const Vec3 v = 0.5 * normal + tangential;
  // mu dv_n = 2 of 3: a third of the tangential velocity is left; the normal part is kept.
  const Vec3 slowed = coulomb_velocity_friction(v, normal, 4.0, 0.5);
  EXPECT_LT((slowed - (0.5 * normal + tangential / 3.0)).norm(), 1e-14);
  // mu dv_n beyond |v_t|: it stops (sticks), never reverses.
  const Vec3 stuck = coulomb_velocity_friction(v, normal, 10.0, 0.5);
  EXPECT_LT((stuck - 0.5 * normal).norm(), 1e-14);
  // No friction, or no tangential motion: unchanged.
  EXPECT_LT((coulomb_velocity_friction(v, normal, 4.0, 0.0) - v).norm(), 1e-15);
  EXPECT_LT((coulomb_velocity_friction(2.0 * normal, normal, 4.0, 0.5) - 2.0 * normal).norm(),
            1e-15);
}

}  // namespace
}  // namespace drape
