// XPBD's multiplier update and the contact constraint built from the collision energy: closed
// forms and finite differences.
#include <gtest/gtest.h>

#include "integrators/xpbd/xpbd_constraints.hpp"
#include "tests/support/test_support.hpp"

namespace drape {
namespace {

std::shared_ptr<const Dummy> sphere() {
  return std::make_shared<const Dummy>(make_dummy(
      nlohmann::json{{"builtin", "sphere"}, {"radius", 0.05}, {"center", {0.0, 1.0, 0.0}}},
      "test", "dummy", "."));
}

// Points a little outside the sphere (within the 1 cm threshold), away from the poles.
std::vector<Vec3> shell_points() {
  std::vector<Vec3> points;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> angle(-3.0, 3.0), polar(0.6, 2.5), gap(0.001, 0.008);
  for (int k = 0; k < 20; ++k) {
    const double theta = angle(rng), phi = polar(rng), r = 0.05 + gap(rng);
    points.emplace_back(r * std::sin(phi) * std::sin(theta), 1.0 + r * std::cos(phi),
                        r * std::sin(phi) * std::cos(theta));
  }
  return points;
}

// For a linear constraint one update solves C(x + w grad C dlambda) + alpha~ dlambda = 0 exactly:
// a particle on a spring to a fixed point, along the spring.
TEST(XpbdConstraints, OneUpdateSolvesALinearConstraint) {
  const double w = 1000.0, alpha = 1e-3 / (1e-3 * 1e-3);  // 1/k / h^2 with k = 1000, h = 1 ms
  const double extension = 0.01;
  const double dlambda = xpbd_multiplier_step(extension, w, alpha, 0.0, 0.0, 0.0);
  EXPECT_NEAR(extension + w * dlambda + alpha * dlambda, 0.0, 1e-15);
  // With damping gamma and a motion grad C . (x - x_prev) = m the update also solves
  // C + alpha~ lambda + gamma grad C . (x_new - x_prev) = 0.
  const double gamma = 0.3, motion = 0.002;
  const double damped = xpbd_multiplier_step(extension, w, alpha, 0.0, gamma, motion);
  EXPECT_NEAR(extension + w * damped + alpha * damped + gamma * (motion + w * damped), 0.0,
              1e-15);
}

TEST(XpbdConstraints, ParticleModelContactIsThresholdMinusDistance) {
  const auto dummy = sphere();
  const CollisionParams params{0.01, 1000.0, CollisionModel::particle};
  const Collision collision(dummy, params, 1);
  int active = 0;
  for (const Vec3& x : shell_points()) {
    const NearestObjectParticle hit = dummy->nearest_within(x, params.threshold);
    ContactConstraint c;
    ASSERT_EQ(contact_constraint(collision, 0, x, c), hit.index >= 0);
    if (hit.index < 0) continue;
    ++active;
    const Vec3 e = x - dummy->position(hit.index);
    EXPECT_NEAR(c.value, params.threshold - hit.distance, 1e-15);
    EXPECT_LT((c.gradient + e / e.norm()).norm(), 1e-12);
  }
  EXPECT_GT(active, 5);
}

// grad C = -F / (k C) is the gradient of sqrt(2 U / k) for every model.
TEST(XpbdConstraints, ContactGradientIsTheDerivativeOfSqrtTwoEnergyOverStiffness) {
  for (const CollisionModel model :
       {CollisionModel::particle, CollisionModel::surface, CollisionModel::smooth}) {
    const CollisionParams params{0.01, 1000.0, model};
    const Collision collision(sphere(), params, 1);
    const auto constraint_value = [&](const Eigen::VectorXd& x) {
      return std::sqrt(2.0 * collision.energy(0, x) / params.stiffness);
    };
    int active = 0;
    for (const Vec3& x : shell_points()) {
      ContactConstraint c;
      if (!contact_constraint(collision, 0, x, c)) {
        EXPECT_EQ(collision.energy(0, x), 0.0);
        continue;
      }
      ++active;
      EXPECT_NEAR(c.value, constraint_value(x), 1e-15);
      const Eigen::VectorXd fd = testing::fd_gradient(constraint_value, x, 1e-7);
      EXPECT_LT((fd - c.gradient).norm(), 1e-6 * std::max(1.0, c.gradient.norm()))
          << static_cast<int>(model);
    }
    EXPECT_GT(active, 5) << static_cast<int>(model);
  }
}

}  // namespace
}  // namespace drape
