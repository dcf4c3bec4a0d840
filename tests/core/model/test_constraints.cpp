// Fixed particles (docs/model.md section 5): the sorted set, the mask, and the rows each
// operation replaces, checked against a trajectory whose derivatives are known in closed form.
#include "core/model/constraints.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace drape {
namespace {

/// p(t) = c + a (cos wt, sin wt, 0): |p'| = a w, p'' = -w^2 (p - c).
class Circle final : public Trajectory {
 public:
  Circle(const Vec3& centre, double radius, double omega)
      : m_centre(centre), m_radius(radius), m_omega(omega) {}
  Vec3 position(double t) const override {
    return m_centre + m_radius * Vec3(std::cos(m_omega * t), std::sin(m_omega * t), 0.0);
  }
  Vec3 velocity(double t) const override {
    return m_radius * m_omega * Vec3(-std::sin(m_omega * t), std::cos(m_omega * t), 0.0);
  }
  Vec3 acceleration(double t) const override {
    return -m_omega * m_omega * (position(t) - m_centre);
  }

 private:
  Vec3 m_centre;
  double m_radius;
  double m_omega;
};

Eigen::VectorXd ramp(int n) { return Eigen::VectorXd::LinSpaced(3 * n, 1.0, 3.0 * n); }

TEST(Constraints, FixAndReleaseKeepTheIndicesSortedAndTheMaskInStep) {
  ConstraintSet set(6);
  set.fix_at(4, Vec3::Zero());
  set.fix_at(1, Vec3::Zero());
  set.fix_at(3, Vec3::Zero());
  set.fix_at(4, Vec3::Ones());  // refixing replaces the trajectory, not the index
  EXPECT_EQ(set.fixed_particles(), (std::vector<int>{1, 3, 4}));
  EXPECT_EQ(set.mask(), (std::vector<unsigned char>{0, 1, 0, 1, 1, 0}));
  EXPECT_EQ(set.trajectory(4)->position(0.0), Vec3::Ones());
  set.release(3);
  set.release(0);  // not fixed: no effect
  EXPECT_EQ(set.fixed_particles(), (std::vector<int>{1, 4}));
  EXPECT_EQ(set.mask(), (std::vector<unsigned char>{0, 1, 0, 0, 1, 0}));
  EXPECT_FALSE(set.is_fixed(3));
  EXPECT_EQ(set.trajectory(3), nullptr);
  EXPECT_TRUE(set.is_fixed(1));
}

TEST(Constraints, ProjectPutsFixedParticlesOnTheirTrajectoryAndLeavesTheOthers) {
  ConstraintSet set(4);
  const Vec3 centre(0.1, 0.2, 0.3);
  set.fix(2, std::make_shared<Circle>(centre, 0.5, 2.0));
  set.fix_at(0, Vec3(7.0, 8.0, 9.0));
  Eigen::VectorXd x = ramp(4);
  Eigen::VectorXd v = -ramp(4);
  const Eigen::VectorXd x0 = x;
  const Eigen::VectorXd v0 = v;
  const double t = 0.7;
  set.project(t, x, v);
  EXPECT_EQ(Vec3(x.segment<3>(0)), Vec3(7.0, 8.0, 9.0));
  EXPECT_EQ(Vec3(v.segment<3>(0)), Vec3::Zero());
  EXPECT_NEAR((x.segment<3>(6) - centre).norm(), 0.5, 1e-15);
  EXPECT_NEAR(x[6], centre.x() + 0.5 * std::cos(1.4), 1e-15);
  EXPECT_NEAR(v[7], 0.5 * 2.0 * std::cos(1.4), 1e-15);
  EXPECT_EQ(x.segment<3>(3), x0.segment<3>(3));
  EXPECT_EQ(x.segment<3>(9), x0.segment<3>(9));
  EXPECT_EQ(v.segment<3>(3), v0.segment<3>(3));
  EXPECT_EQ(v.segment<3>(9), v0.segment<3>(9));
}

TEST(Constraints, RightHandSideRowsBecomeTheTrajectorysDerivatives) {
  ConstraintSet set(3);
  const Vec3 centre(0.0, 1.0, 0.0);
  set.fix(1, std::make_shared<Circle>(centre, 0.25, 3.0));
  Eigen::VectorXd x_dot = ramp(3);
  Eigen::VectorXd v_dot = 2.0 * ramp(3);
  const double t = 0.4;
  set.apply_to_rhs(t, x_dot, v_dot);
  const Circle circle(centre, 0.25, 3.0);
  EXPECT_EQ(Vec3(x_dot.segment<3>(3)), circle.velocity(t));
  // Centripetal acceleration: |p''| = a w^2, pointing at the centre.
  EXPECT_NEAR(v_dot.segment<3>(3).norm(), 0.25 * 9.0, 1e-14);
  EXPECT_NEAR(v_dot.segment<3>(3).dot(circle.position(t) - centre), -0.25 * 0.25 * 9.0, 1e-14);
  EXPECT_EQ(x_dot.segment<3>(0), ramp(3).segment<3>(0));
  EXPECT_EQ(v_dot.segment<3>(6), 2.0 * ramp(3).segment<3>(6));
}

TEST(Constraints, ZeroFixedClearsOnlyFixedRows) {
  ConstraintSet set(4);
  set.fix_at(1, Vec3::Ones());
  set.fix_at(3, Vec3::Ones());
  Eigen::VectorXd r = ramp(4);
  set.zero_fixed(r);
  EXPECT_EQ(r.segment<3>(3).norm(), 0.0);
  EXPECT_EQ(r.segment<3>(9).norm(), 0.0);
  EXPECT_EQ(r.segment<3>(0), ramp(4).segment<3>(0));
  EXPECT_EQ(r.segment<3>(6), ramp(4).segment<3>(6));
}

TEST(Constraints, MaxSpeedIsTheFastestPrescribedMotion) {
  ConstraintSet set(5);
  EXPECT_EQ(set.max_speed(0.0), 0.0) << "no fixed particle";
  set.fix_at(0, Vec3::Ones());
  EXPECT_EQ(set.max_speed(1.0), 0.0) << "a pin does not move";
  set.fix(2, std::make_shared<Circle>(Vec3::Zero(), 0.5, 2.0));   // speed 1.0
  set.fix(4, std::make_shared<Circle>(Vec3::Zero(), 0.3, 10.0));  // speed 3.0
  EXPECT_NEAR(set.max_speed(0.3), 3.0, 1e-14);
  set.release(4);
  EXPECT_NEAR(set.max_speed(0.3), 1.0, 1e-14);
}

}  // namespace
}  // namespace drape
