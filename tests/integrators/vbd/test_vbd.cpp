// Vertex Block Descent: its step tends to converged backward Euler as the sweeps go on, it
// settles on the Newton equilibrium, gains no energy, and refuses bad keys.
#include <gtest/gtest.h>

#include "integrators/implicit_euler/implicit_euler.hpp"
#include "integrators/registry/options_reader.hpp"
#include "integrators/registry/registry.hpp"
#include "integrators/vbd/vbd.hpp"
#include "tests/support/backward_euler_reference.hpp"
#include "tests/support/swinging_sheet.hpp"
#include "tests/support/test_support.hpp"

namespace drape {
namespace {

constexpr double frame = 1.0 / 30.0;

IntegratorOptions vbd_options(double dt, int iterations, const std::string& init = "inertia",
                              bool chebyshev = false) {
  IntegratorOptions o;
  o.name = "vbd";
  o.dt = dt;
  o.settings = {{"iterations", iterations}, {"init", init}, {"chebyshev", chebyshev}};
  return o;
}

// Largest position distance of one VBD step of `iterations` sweeps from y0 to `reference`.
double distance_after(ClothSystem& s, const Eigen::VectorXd& y0, const Eigen::VectorXd& reference,
                      int iterations, bool chebyshev) {
  Vbd method(s, vbd_options(frame, iterations, "inertia", chebyshev));
  method.reset(0.0, y0);
  method.step(frame);
  const Eigen::Index n3 = y0.size() / 2;
  return (method.state() - reference).head(n3).lpNorm<Eigen::Infinity>();
}

// The distance falls with the sweeps, plain and Chebyshev-accelerated, to below 1e-6 m after
// the last count (or to the round-off floor, 1e-12 m, earlier).
void expect_converges_to_backward_euler(ClothSystem& s, const Eigen::VectorXd& y0,
                                        std::vector<int> plain, std::vector<int> chebyshev) {
  const Eigen::VectorXd reference = testing::backward_euler_step(s, y0, frame);
  for (const bool accelerated : {false, true}) {
    double previous = distance_after(s, y0, reference, 1, accelerated);
    for (const int iterations : accelerated ? chebyshev : plain) {
      const double d = distance_after(s, y0, reference, iterations, accelerated);
      EXPECT_TRUE(d < previous || d < 1e-12)
          << iterations << " iterations, chebyshev " << accelerated << ": " << d;
      previous = d;
    }
    EXPECT_LT(previous, 1e-6) << "chebyshev " << accelerated;
  }
}

// Measured distances (m) after 10, 100, 1000 sweeps: 1.2e-2, 9.6e-3, 1.4e-3 plain, 1.2e-2,
// 5.3e-3, 1.6e-5 with Chebyshev; below 1e-6 at 6000 plain, 4000 Chebyshev.
TEST(Vbd, SwingingSheetStepConvergesToConvergedBackwardEuler) {
  auto sheet = testing::swinging_sheet(1.0);
  // A moving start: three backward-Euler steps from rest.
  Eigen::VectorXd y = sheet->initial_state(0.0);
  for (int k = 0; k < 3; ++k) y = testing::backward_euler_step(*sheet, y, frame);
  expect_converges_to_backward_euler(*sheet, y, {10, 100, 1000, 6000}, {10, 100, 1000, 4000});
}

// Measured: 2.4e-3, 1.4e-5, 7e-16 m after 10, 100, 1000 sweeps; Chebyshev 9.6e-4, 9.5e-14.
TEST(Vbd, SheetOnASphereStepConvergesToConvergedBackwardEuler) {
  auto pressed = testing::cloth_against_sphere(CollisionModel::smooth);
  expect_converges_to_backward_euler(*pressed, pressed->initial_state(0.0), {10, 100, 1000},
                                     {10, 100});
}

// Settled, a step from rest must return its start. The starts x_n (`previous`), x_n + h v_n
// (`velocity`, the same at rest) and `adaptive` (no acceleration at rest: the same) are then a
// fixed point; the inertial start x_n + h^2 g is not, and a finite number of sweeps leaves the
// cloth where they bring it back from x_n + h^2 g, short of the equilibrium.
void expect_settles_on_newton_equilibrium(ClothSystem& s) {
  const Eigen::VectorXd expected = testing::newton_equilibrium(s);
  EXPECT_GT((expected - s.cloth().rest_positions).lpNorm<Eigen::Infinity>(), 0.003) << "it sags";
  for (const char* init : {"previous", "velocity", "adaptive", "inertia"}) {
    Vbd method(s, vbd_options(frame, 10, init));
    const double d = (testing::settle(method, s) - expected).lpNorm<Eigen::Infinity>();
    if (std::string(init) == "inertia")
      EXPECT_GT(d, 1e-6) << init;
    else
      EXPECT_LT(d, 1e-6) << init;
  }
}

TEST(Vbd, SettlesOnTheNewtonEquilibrium) {
  expect_settles_on_newton_equilibrium(*testing::pinned_test_cloth(0.02, 0.002));
  ClothParams chain = testing::small_cloth(1, 8);
  chain.damping_spring = 0.02;
  chain.damping_air = 0.002;
  ClothSystem s(build_cloth(chain), nullptr, ForceParams{});
  s.constraints().fix_at(0, s.cloth().rest_positions.segment<3>(0));
  expect_settles_on_newton_equilibrium(s);
}

// The swinging sheet's cloth (the drape scenes' mass and stiffness, stiff at the frame step:
// k h^2 / m ~ 900) hanging undamped from its top corners.
std::unique_ptr<ClothSystem> undamped_hanging_sheet() {
  ClothParams p = testing::small_cloth(12, 12);
  p.particle_mass = 6e-5;
  p.k_structural = p.k_shear = 50.0;
  p.k_bending = 0.0;
  auto s = std::make_unique<ClothSystem>(build_cloth(p), nullptr, ForceParams{});
  s->constraints().fix_at(0, s->cloth().rest_positions.segment<3>(0));
  s->constraints().fix_at(11, s->cloth().rest_positions.segment<3>(33));
  return s;
}

// The highest total energy over 90 frames of ten sweeps, relative to the start.
double highest_energy_gain(ClothSystem& s, const char* init) {
  const Eigen::Index n3 = 3 * s.num_particles();
  Vbd method(s, vbd_options(frame, 10, init));
  method.reset(0.0, s.initial_state(0.0));
  auto energy = [&] {
    const Eigen::VectorXd& y = method.state();
    return s.energy(y.head(n3), y.tail(n3)).total();
  };
  const double start = energy();
  double highest = start;
  for (int k = 0; k < 90; ++k) {
    method.step(10.0);
    highest = std::max(highest, energy());
  }
  return (highest - start) / std::abs(start);
}

// Backward Euler dissipates; unconverged sweeps must not add energy either. From x_n and from
// x_n + h v_n the undamped hanging cloth never rises above its start. From the inertial start
// x_n + h v_n + h^2 g, ten sweeps leave part of a free fall's step in the result: the springs
// near the pins stretch with no force having done the work, and the cloth gains; the adaptive
// start, inertial while the cloth falls, gains on the stiff sheet too. Hence the default
// `velocity` (docs/integrators/vbd.md).
TEST(Vbd, UndampedHangingClothGainsNoEnergy) {
  auto soft = testing::pinned_test_cloth();
  auto stiff = undamped_hanging_sheet();
  for (const char* init : {"previous", "velocity"}) {
    EXPECT_LE(highest_energy_gain(*soft, init), 1e-12) << init;
    EXPECT_LE(highest_energy_gain(*stiff, init), 1e-12) << init;
  }
  EXPECT_GT(highest_energy_gain(*soft, "inertia"), 1e-4);
  EXPECT_GT(highest_energy_gain(*stiff, "inertia"), 1e-2);
  EXPECT_GT(highest_energy_gain(*stiff, "adaptive"), 1e-2);
}

TEST(Vbd, CountsItsSweeps) {
  auto s = testing::pinned_test_cloth();
  Vbd method(*s, vbd_options(frame, 7));
  method.reset(0.0, s->initial_state(0.0));
  method.step(1.0);
  method.step(1.0);
  EXPECT_EQ(method.counters().newton_iters, 14);
  EXPECT_EQ(method.counters().steps, 2);
}

std::string error_of(const nlohmann::json& o) {
  return testing::input_error_message(
      [&] { read_integrator_options(o, "scene.json", "integrator"); });
}

TEST(Vbd, BadKeysAreInputErrorsNamingTheField) {
  const nlohmann::json base = {{"name", "vbd"}, {"dt", frame}};
  auto with = [&](const char* key, const nlohmann::json& value) {
    nlohmann::json o = base;
    o[key] = value;
    return error_of(o);
  };
  EXPECT_EQ(error_of(base), "no error");
  for (const nlohmann::json& bad :
       {nlohmann::json(0), nlohmann::json(1000001), nlohmann::json(2.5)})
    EXPECT_NE(with("iterations", bad).find("integrator.iterations"), std::string::npos) << bad;
  for (const double bad : {0.0, 1.0, -0.5, 1.5})
    EXPECT_NE(with("rho", bad).find("integrator.rho"), std::string::npos) << bad;
  EXPECT_NE(with("init", "zero").find("integrator.init"), std::string::npos);
  EXPECT_NE(with("chebyshev", 1).find("integrator.chebyshev"), std::string::npos);
  const IntegratorOptions o =
      read_integrator_options({{"name", "vbd"}, {"dt", frame}, {"init", "adaptive"}, {"rho", 0.5}},
                              "scene.json", "integrator");
  EXPECT_EQ(o.setting_choice("init", vbd_declaration().keys), "adaptive");
  EXPECT_EQ(o.setting_number("rho", vbd_declaration().keys), 0.5);
  EXPECT_EQ(o.setting_integer("iterations", vbd_declaration().keys), 20);
  EXPECT_EQ(find_integrator("vbd")->family, "optimisation");
}

}  // namespace
}  // namespace drape
