// arkode-dirk's default table settles from a hard start at one step per Kinect frame
// (docs/integrators/arkode.md, "Tables"; docs/findings/dirk_default.md, "One spring"): the
// drape cloth's own spring, pinned at one end, released horizontal at rest stretched 1 % and
// stepped at 1/30 s, comes to rest hanging on its static equilibrium, whose energy is known in
// closed form.
#include <gtest/gtest.h>

#include <cmath>

#include "core/model/cloth_system.hpp"
#include "integrators/registry/registry.hpp"
#include "tests/support/test_support.hpp"

namespace drape {
namespace {

// One particle on one spring, the drape cloth's (experiments/scenes/swinging_chain.json with
// cloth.cols = 2), horizontal, its first particle pinned.
struct PinnedSpring {
  double mass = 6e-5, k = 50.0, rest = 0.02, pin_height = 1.3, g = 9.81;
  std::unique_ptr<ClothSystem> system() const {
    ClothParams p;
    p.rows = 1;
    p.cols = 2;
    p.spacing = rest;
    p.origin = Vec3(0.0, pin_height, 0.0);
    p.col_dir = Vec3::UnitX();
    p.row_dir = Vec3::UnitZ();
    p.particle_mass = mass;
    p.k_structural = k;
    p.damping_spring = 0.01;
    p.damping_air = 1e-4;
    auto s = std::make_unique<ClothSystem>(build_cloth(p), nullptr, ForceParams{});
    s->constraints().fix_at(0, s->cloth().rest_positions.segment<3>(0));
    return s;
  }
  // At rest with the spring stretched by the weight, m g / k: spring energy (m g)^2 / 2k, the
  // two particles' gravity energy m g (y_pin + y_particle).
  double equilibrium_energy() const {
    const double sag = mass * g / k;
    return 0.5 * k * sag * sag + mass * g * (2.0 * pin_height - rest - sag);
  }
};

double energy_after(const IntegratorOptions& o, double stretch, double t_end) {
  const PinnedSpring spring;
  auto s = spring.system();
  Eigen::VectorXd y0 = s->initial_state(0.0);
  y0[3] = (1.0 + stretch) * spring.rest;  // the particle's x
  auto method = make_integrator(o, *s);
  method->reset(0.0, y0);
  const Eigen::VectorXd y = testing::run_until(*method, t_end);
  const Eigen::Index n3 = 3 * s->num_particles();
  return s->energy(y.head(n3), y.tail(n3)).total();
}

IntegratorOptions at_a_kinect_frame(const std::string& table) {
  IntegratorOptions o;
  o.name = "arkode-dirk";
  o.table = table;  // empty: the default
  o.dt = 1.0 / 30.0;
  validate_integrator_choice(o, "test", "integrator");
  return o;
}

TEST(DefaultDirkTable, SettlesFromASpringStretchedOnePercentAtRest) {
  const PinnedSpring spring;
  // The start lies m g L above the hanging particle, with 0.5 k (0.01 L)^2 in the spring.
  const double excess =
      energy_after(at_a_kinect_frame(""), 0.01, 0.0) - spring.equilibrium_energy();
  const double sag = spring.mass * spring.g / spring.k;
  ASSERT_NEAR(excess,
              spring.mass * spring.g * (spring.rest + sag) +
                  0.5 * spring.k * (std::pow(0.01 * spring.rest, 2) - sag * sag),
              1e-15);
  // Measured (docs/findings/dirk_default.md, "One spring"): the default, TR-BDF2, is 4.9e-7 J
  // above the equilibrium at 2 s, still swinging slowly as the pendulum it is; 2e-6 J leaves a
  // factor 4 and is a sixth of the start's 1.28e-5 J.
  const double left = energy_after(at_a_kinect_frame(""), 0.01, 2.0) - spring.equilibrium_energy();
  EXPECT_LT(std::abs(left), 2e-6);
  // Why not KVAERNO_4_2_3, which also settles on the drape: at 2 s it is 2.7e-5 J above the
  // equilibrium, more than it started with, the particle jumping through its pin every step.
  const double kvaerno =
      energy_after(at_a_kinect_frame("ARKODE_KVAERNO_4_2_3"), 0.01, 2.0) - spring.equilibrium_energy();
  EXPECT_GT(kvaerno, excess);
}

}  // namespace
}  // namespace drape
