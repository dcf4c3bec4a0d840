// The `smooth` collision model: force against energy, Jacobian against force (finite
// differences), the definite Jacobian, no pairing, and penetration correction onto G = 0.
#include "core/collision/smooth_contact.hpp"

#include <gtest/gtest.h>

#include <random>

#include "core/collision/collision.hpp"
#include "core/dummy/dummy_sources.hpp"

namespace drape {
namespace {

TEST(SmoothContact, PotentialIsC2AtTheThresholdAndMatchesTheParticleForceAtContact) {
  const double k = 1000.0, delta = 0.01;
  EXPECT_EQ(smooth_contact_energy(delta, k, delta), 0.0);
  EXPECT_NEAR(smooth_contact_slope(delta - 1e-9, k, delta), 0.0, 1e-12);
  EXPECT_NEAR(smooth_contact_curvature(delta - 1e-9, k, delta), 0.0, 1e-3);
  EXPECT_DOUBLE_EQ(-smooth_contact_slope(0.0, k, delta), k * delta);  // section 4.5 at d = 0
  EXPECT_DOUBLE_EQ(smooth_contact_curvature(0.0, k, delta), 2.0 * k);
  // Off G = 0, where the third derivative jumps (the continuation's join, tested below).
  for (const double g : {-0.02, -0.001, -1e-6, 1e-6, 0.004, 0.0099}) {
    const double h = 1e-7;
    EXPECT_NEAR(smooth_contact_slope(g, k, delta),
                (smooth_contact_energy(g + h, k, delta) - smooth_contact_energy(g - h, k, delta)) / (2 * h),
                1e-6);
    EXPECT_NEAR(smooth_contact_curvature(g, k, delta),
                (smooth_contact_slope(g + h, k, delta) - smooth_contact_slope(g - h, k, delta)) / (2 * h),
                1e-5);
  }
}

// Inside (G < 0) the potential continues as the cubic's Taylor polynomial at 0: value, slope
// and curvature meet at G = 0, and the curvature stays 2 k however deep the particle is.
TEST(SmoothContact, QuadraticContinuationInsideIsC2AtContactWithCurvatureTwoK) {
  const double k = 200.0, delta = 0.01, eps = 1e-14;
  EXPECT_NEAR(smooth_contact_energy(-eps, k, delta), k * delta * delta / 3.0, 1e-12);
  EXPECT_NEAR(smooth_contact_energy(eps, k, delta), k * delta * delta / 3.0, 1e-12);
  EXPECT_NEAR(smooth_contact_slope(-eps, k, delta), smooth_contact_slope(eps, k, delta), 1e-9);
  EXPECT_NEAR(smooth_contact_curvature(-eps, k, delta), smooth_contact_curvature(eps, k, delta), 1e-6);
  for (const double g : {-1e-4, -0.01, -0.1, -1.0}) {
    EXPECT_EQ(smooth_contact_curvature(g, k, delta), 2.0 * k) << g;
    EXPECT_DOUBLE_EQ(smooth_contact_slope(g, k, delta), -k * delta + 2.0 * k * g) << g;
  }
}

struct Fixture {
  explicit Fixture(const nlohmann::json& spec)
      : dummy(std::make_shared<const Dummy>(make_dummy(spec, "test", "dummy", "."))),
        surface(dummy->sections()),
        collision(dummy, CollisionParams{0.01, 1000.0, CollisionModel::smooth}, 1) {}
  /// A point at gap about `offset` from the surface at height y and angle theta.
  Vec3 at(double y, double theta, double offset) const {
    const Eigen::Vector2d c = surface.axis(y);
    const double r = surface.radius(y, theta) + offset;
    return {c.x() + r * std::sin(theta), y, c.y() + r * std::cos(theta)};
  }
  std::shared_ptr<const Dummy> dummy;
  SmoothSurface surface;
  Collision collision;
};

TEST(SmoothContact, ForceIsMinusTheEnergyGradientAndJacobianItsDerivative) {
  for (const auto& spec : {nlohmann::json{{"builtin", "dress-form"}},
                           nlohmann::json{{"builtin", "sphere"}, {"radius", 0.2}}}) {
    Fixture f(spec);
    const auto& ys = f.dummy->sections().y;
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    int active = 0;
    for (int trial = 0; trial < 300; ++trial) {
      const double y = ys.back() - 0.01 + (ys.front() - ys.back() + 0.02) * u(rng);
      const Vec3 x = f.at(y, 2.0 * M_PI * u(rng), 0.015 * (u(rng) - 0.3));
      const Vec3 force = f.collision.force(0, x);
      const Mat3 exact = f.collision.jacobian(0, x, false);
      if (force.norm() > 0.0) ++active;
      const double h = 1e-7;
      Vec3 fd_force;
      Mat3 fd_jacobian;
      for (int a = 0; a < 3; ++a) {
        const Vec3 e = h * Vec3::Unit(a);
        fd_force[a] = -(f.collision.energy(0, x + e) - f.collision.energy(0, x - e)) / (2 * h);
        fd_jacobian.col(a) = (f.collision.force(0, x + e) - f.collision.force(0, x - e)) / (2 * h);
      }
      EXPECT_LT((fd_force - force).norm(), 1e-5 * (1.0 + force.norm())) << spec << " " << x.transpose();
      EXPECT_LT((fd_jacobian - exact).norm(), 1e-3 * (1.0 + exact.norm())) << spec << " " << x.transpose();
      // The definite Jacobian: negative semi-definite, and the exact one wherever that already is.
      const Mat3 definite = f.collision.jacobian(0, x, true);
      Eigen::SelfAdjointEigenSolver<Mat3> eig(definite);
      EXPECT_LT(eig.eigenvalues().maxCoeff(), 1e-9 * (1.0 + definite.norm()));
      Eigen::SelfAdjointEigenSolver<Mat3> eig_exact(exact);
      if (eig_exact.eigenvalues().maxCoeff() <= 0.0) {
        // computeDirect's eigenvectors carry a relative error of about 1e-6.
        EXPECT_LE((definite - exact).norm(), 1e-5 * exact.norm());
      }
    }
    EXPECT_GT(active, 100) << spec;
  }
}

TEST(SmoothContact, PairingLeavesTheSmoothModelUnpaired) {
  Fixture f(nlohmann::json{{"builtin", "dress-form"}});
  const Vec3 x = f.at(1.1, 0.3, 0.004);
  const Vec3 before = f.collision.force(0, x);
  f.collision.pair_contacts(x);
  EXPECT_EQ(f.collision.paired(0), -1);
  EXPECT_EQ(f.collision.force(0, x + Vec3(0.001, 0.0, 0.0)),
            Collision(f.dummy, f.collision.params(), 1).force(0, x + Vec3(0.001, 0.0, 0.0)));
  EXPECT_EQ(f.collision.force(0, x), before);
}

TEST(SmoothContact, PenetrationCorrectionMovesOntoTheSurfaceAndStopsTheInwardVelocity) {
  Fixture f(nlohmann::json{{"builtin", "sphere"}, {"radius", 0.2}});
  // On the side (moves radially), near the top (moves up) and just outside (stays).
  for (const auto& [y, offset] : {std::pair{0.05, -0.004}, std::pair{0.199, -0.002}, std::pair{0.0, 0.001}}) {
    Vec3 x = f.at(y, 0.7, offset);
    const double y_top = f.dummy->sections().y.front();
    if (y > y_top) x = Vec3(0.0, y_top - 0.001, 0.0);
    const Vec3 start = x;
    Vec3 v(0.0, -1.0, 0.0);
    const bool corrected = f.collision.correct_penetration(0, x, v);
    const SmoothGap g = f.surface.gap(x);
    if (f.surface.gap(start).gap >= 0.0) {
      EXPECT_FALSE(corrected);
      EXPECT_EQ(x, start);
      continue;
    }
    EXPECT_TRUE(corrected) << y;
    EXPECT_NEAR(g.gap, 0.0, 1e-12) << y;
    EXPECT_GE(v.dot(g.gradient.normalized()), -1e-12) << y;
    EXPECT_LT((x - start).norm(), 0.01) << y;  // the nearby surface, not the far side
  }
}

}  // namespace
}  // namespace drape
