// The soft hold's trajectory (docs/manipulations.md, "Soft hold"): C1 from the particle's free
// path to the hand, checked against its closed form and by finite differences.
#include <gtest/gtest.h>

#include "core/manipulations/hold_ramp.hpp"

namespace drape {
namespace {

// q(t) = a + b t + c t^2: a hand moving with constant acceleration.
class Parabola final : public Trajectory {
 public:
  Parabola(Vec3 a, Vec3 b, Vec3 c) : m_a(a), m_b(b), m_c(c) {}
  Vec3 position(double t) const override { return m_a + m_b * t + m_c * t * t; }
  Vec3 velocity(double t) const override { return m_b + 2.0 * m_c * t; }
  Vec3 acceleration(double) const override { return 2.0 * m_c; }

 private:
  Vec3 m_a, m_b, m_c;
};

const Vec3 x0(0.1, 1.0, 0.2), v0(0.3, -0.2, 0.1);
constexpr double t0 = 0.5, ramp = 0.1;

RampedTrajectory ramped() {
  return RampedTrajectory(std::make_shared<Parabola>(Vec3(0.2, 1.1, 0.3), Vec3(0.5, 0.0, -0.4),
                                                     Vec3(0.0, 1.0, 2.0)),
                          x0, v0, t0, ramp);
}

TEST(HoldRamp, StartsOnTheParticleWithItsVelocity) {
  const RampedTrajectory p = ramped();
  EXPECT_LT((p.position(t0) - x0).norm(), 1e-15) << "no position jump at the hold";
  EXPECT_LT((p.velocity(t0) - v0).norm(), 1e-14) << "no velocity jump at the hold";
}

TEST(HoldRamp, ReachesTheHandAtTheEndOfTheRampAndStaysOnIt) {
  const RampedTrajectory p = ramped();
  const Parabola q(Vec3(0.2, 1.1, 0.3), Vec3(0.5, 0.0, -0.4), Vec3(0.0, 1.0, 2.0));
  // (t0 + ramp itself may round to tau just below 1; the blend there differs by rounding only.)
  for (const double t : {t0 + 1.0001 * ramp, t0 + 1.5 * ramp, t0 + 3.0 * ramp}) {
    EXPECT_LT((p.position(t) - q.position(t)).norm(), 1e-15) << t;
    EXPECT_LT((p.velocity(t) - q.velocity(t)).norm(), 1e-15) << t;
    EXPECT_LT((p.acceleration(t) - q.acceleration(t)).norm(), 1e-15) << t;
  }
  // Position and velocity are continuous at the end of the ramp (C1); the acceleration jumps
  // by s''(1) (q - free) = -6 / T^2 (q - free), finite.
  const double t = t0 + ramp - 1e-9;
  EXPECT_LT((p.position(t) - q.position(t)).norm(), 1e-12);
  EXPECT_LT((p.velocity(t) - q.velocity(t)).norm(), 1e-6);
}

TEST(HoldRamp, HalfwayIsTheMeanOfFreePathAndHand) {
  const RampedTrajectory p = ramped();
  const Parabola q(Vec3(0.2, 1.1, 0.3), Vec3(0.5, 0.0, -0.4), Vec3(0.0, 1.0, 2.0));
  const double t = t0 + 0.5 * ramp;  // smoothstep(1/2) = 1/2
  const Vec3 expected = 0.5 * (x0 + v0 * (t - t0)) + 0.5 * q.position(t);
  EXPECT_LT((p.position(t) - expected).norm(), 1e-15);
}

TEST(HoldRamp, VelocityAndAccelerationAreTheDerivatives) {
  const RampedTrajectory p = ramped();
  const double h = 1e-6;
  for (const double u : {0.1, 0.3, 0.5, 0.8, 0.95}) {
    const double t = t0 + u * ramp;
    const Vec3 dx = (p.position(t + h) - p.position(t - h)) / (2 * h);
    const Vec3 dv = (p.velocity(t + h) - p.velocity(t - h)) / (2 * h);
    EXPECT_LT((dx - p.velocity(t)).norm(), 1e-7) << u;
    EXPECT_LT((dv - p.acceleration(t)).norm(), 1e-5) << u;
  }
}

}  // namespace
}  // namespace drape
