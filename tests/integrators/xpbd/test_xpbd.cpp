// XPBD with small steps: converged backward Euler, first order in the substep, static
// equilibria and contact rest, no energy gain, fixed particles, bad keys, deterministic sweeps.
#include <gtest/gtest.h>

#include "integrators/explicit/leapfrog.hpp"
#include "integrators/registry/options_reader.hpp"
#include "integrators/implicit_euler/implicit_euler.hpp"
#include "integrators/registry/registry.hpp"
#include "integrators/xpbd/xpbd.hpp"
#include "tests/support/backward_euler_reference.hpp"
#include "tests/support/swinging_sheet.hpp"
#include "tests/support/test_support.hpp"

namespace drape {
namespace {

IntegratorOptions xpbd_options(double dt, long substeps, long iterations,
                               const std::string& sweep = "gauss-seidel") {
  IntegratorOptions o;
  o.name = "xpbd";
  o.dt = dt;
  o.settings = {{"substeps", substeps}, {"iterations", iterations}, {"sweep", sweep}};
  return o;
}

// The state at t_end of xpbd with `o` from y0 at t = 0.
Eigen::VectorXd run(ClothSystem& s, const IntegratorOptions& o, const Eigen::VectorXd& y0,
                    double t_end) {
  auto method = std::make_unique<Xpbd>(s, o);
  method->reset(0.0, y0);
  return testing::run_until(*method, t_end);
}

double position_distance(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return (a - b).head(a.size() / 2).lpNorm<Eigen::Infinity>();
}

// A column of 6 particles hanging from its top one, stretched and shaken along the vertical
// only: every spring (structural and bending) stays vertical, its gradient never turns.
TEST(Xpbd, ConvergedStepIsBackwardEulerWhereGradientsKeepTheirDirection) {
  auto s = std::make_unique<ClothSystem>(build_cloth(testing::small_cloth(6, 1)), nullptr,
                                         ForceParams{});
  s->constraints().fix_at(0, s->cloth().rest_positions.segment<3>(0));
  Eigen::VectorXd y0 = s->initial_state(0.0);
  for (int i = 1; i < 6; ++i) y0[3 * i + 1] -= 0.001 * i * i;  // along y only
  const Eigen::VectorXd expected = testing::backward_euler_step(*s, y0, 1.0 / 30.0);
  EXPECT_GT(position_distance(expected, y0), 0.01);  // a large step: the chain falls and rings
  for (const char* sweep : {"gauss-seidel", "jacobi"}) {
    const Eigen::VectorXd y = run(*s, xpbd_options(1.0 / 30.0, 1, 2000, sweep), y0, 1.0 / 30.0);
    EXPECT_LT(position_distance(y, expected), 1e-12) << sweep;
    EXPECT_LT((y - expected).tail(18).lpNorm<Eigen::Infinity>(), 1e-10) << sweep;
  }
}

// Where gradients turn within a step, converged XPBD keeps the residual its update drops
// (Macklin et al. 2016, section 3.5: g = M (x - x~) - grad C^T lambda is taken as 0, but the
// moves were made along the gradients of earlier iterates). It vanishes faster than h^2.
TEST(Xpbd, ConvergedStepIsBackwardEulerUpToTheDroppedResidual) {
  auto s = testing::pinned_test_cloth();
  const Eigen::VectorXd y0 = testing::shaken_state(*s);
  for (const char* sweep : {"gauss-seidel", "jacobi"}) {
    std::vector<double> distance;
    for (const double dt : {1e-2, 1e-3}) {
      const Eigen::VectorXd y = run(*s, xpbd_options(dt, 1, 1000, sweep), y0, dt);
      distance.push_back(position_distance(y, testing::backward_euler_step(*s, y0, dt)));
    }
    // Measured: 2.9e-5 and 2.0e-7 m (Gauss-Seidel), 2.2e-5 and 2.1e-7 m (Jacobi).
    EXPECT_LT(distance[1], 1e-6) << sweep;
    EXPECT_GT(distance[0] / distance[1], 100.0) << sweep;
  }
}

// One iteration per substep: the trajectory converges to leap-frog's at 0.02 ms at first order
// in the substep h.
TEST(Xpbd, SubstepsConvergeAtFirstOrder) {
  auto s = testing::swinging_sheet(1.0, 6);
  const Eigen::VectorXd y0 = s->initial_state(0.0);
  const double t_end = 0.1;
  Leapfrog reference(*s, 2e-5);
  reference.reset(0.0, y0);
  const Eigen::VectorXd expected = testing::run_until(reference, t_end);
  std::vector<double> hs, errors;
  for (const long substeps : {10L, 20L, 40L, 80L, 160L}) {
    hs.push_back(0.01 / static_cast<double>(substeps));
    const Eigen::VectorXd y = run(*s, xpbd_options(0.01, substeps, 1), y0, t_end);
    errors.push_back((y - expected).head(108).norm());
  }
  EXPECT_NEAR(testing::fitted_order(hs, errors), 1.0, 0.2);
}

std::unique_ptr<ClothSystem> chain_pinned_at_both_ends() {
  ClothParams p = testing::small_cloth(1, 8);
  p.damping_spring = 0.02;
  p.damping_air = 0.002;
  auto s = std::make_unique<ClothSystem>(build_cloth(p), nullptr, ForceParams{});
  s->constraints().fix_at(0, s->cloth().rest_positions.segment<3>(0));
  s->constraints().fix_at(7, s->cloth().rest_positions.segment<3>(21));
  return s;
}

// At rest a substep's prediction moves the free particles by h^2 g and its sweeps move them
// back: converged, along turned gradients, which leaves the rest state O(h^2) off the
// equilibrium; with one sweep the spring damping also resists the predicted motion, O(h)
// (docs/integrators/xpbd.md). Measured at 1/30 s, sheet and chain, Gauss-Seidel: 1.4e-4 and
// 5.5e-4 m with 20 x 1, 1.1e-6 and 9.4e-6 m with 20 x 10, 1.0e-8 and 1.0e-7 m with 200 x 10.
// The test takes 100 x 10.
TEST(Xpbd, SettlesOnTheNewtonEquilibrium) {
  for (auto* make : {+[] { return testing::pinned_test_cloth(0.02, 0.002); },
                     +[] { return chain_pinned_at_both_ends(); }}) {
    auto s = make();
    const Eigen::VectorXd expected = testing::newton_equilibrium(*s);
    EXPECT_GT((expected - s->cloth().rest_positions).lpNorm<Eigen::Infinity>(), 0.003);
    for (const char* sweep : {"gauss-seidel", "jacobi"}) {
      std::vector<double> error;
      for (const long substeps : {20L, 100L}) {
        auto method = make_integrator(xpbd_options(1.0 / 30.0, substeps, 10, sweep), *s);
        error.push_back((testing::settle(*method, *s) - expected).lpNorm<Eigen::Infinity>());
        EXPECT_LT(method->time(), 60.0) << sweep << " did not settle";
      }
      EXPECT_LT(error[1], 1e-6) << sweep;
      EXPECT_GT(error[0] / error[1], 15.0) << sweep << ": second order in h (25)";
    }
  }
}

// A particle pressed against a cylinder's side by a horizontal gravity comes to rest where the
// contact carries its weight: delta - d = m g / k_c (particle and surface models: C is linear
// along the normal, and one sweep's rest state is then exact) and k_c (delta - G)^2 / delta = m g
// (smooth: C = sqrt(2 / (3 delta)) (delta - G)^(3/2) is not, and the rest state is O(h^2) off).
TEST(Xpbd, ContactCarriesTheWeightAtTheClosedFormGap) {
  const auto cylinder = std::make_shared<const Dummy>(make_dummy(
      nlohmann::json{{"builtin", "cylinder"}, {"radius", 0.1}, {"center", {0.0, 0.0}},
                     {"y_top", 1.2}, {"y_bottom", 0.8}},
      "test", "dummy", "."));
  const double section_height = cylinder->sections().y[40];
  ClothParams p = testing::small_cloth(1, 1);
  p.origin = Vec3(0.0, section_height, 0.105);  // in front of object particle (40, 0)
  p.damping_air = 0.01;
  const double weight = p.particle_mass * 9.81, k = 1000.0, delta = 0.01;
  for (const CollisionModel model :
       {CollisionModel::particle, CollisionModel::surface, CollisionModel::smooth}) {
    ForceParams forces;
    forces.gravity = Vec3(0.0, 0.0, -9.81);
    forces.collision = {delta, k, model};
    ClothSystem s(build_cloth(p), cylinder, forces);
    const bool smooth = model == CollisionModel::smooth;
    const double expected = smooth ? delta - std::sqrt(weight * delta / k) : delta - weight / k;
    std::vector<double> error;
    for (const long substeps : {20L, 200L}) {
      auto method = make_integrator(xpbd_options(1.0 / 30.0, substeps, 1), s);
      const Eigen::VectorXd x = testing::settle(*method, s);
      error.push_back(std::abs(x[2] - 0.1 - expected));
      EXPECT_NEAR(x[1], section_height, 1e-12) << static_cast<int>(model);
    }
    EXPECT_LT(error[smooth ? 1 : 0], smooth ? 1e-7 : 1e-12) << static_cast<int>(model);
    if (smooth) {
      EXPECT_GT(error[0] / error[1], 50.0) << "second order in h";
    }
  }
}

// The undamped hanging cloth of tests/regression/scenes/hanging_undamped.json at the frame step:
// never above its start energy. XPBD loses energy (its substeps are backward Euler steps); with
// too few substeps and one sweep the springs act softer than k (alpha~ does not dominate
// w |grad C|^2, docs/integrators/xpbd.md), and the model's energy of the stretch they reach
// exceeds the start: 1.5e-4 J of 0.053 J with 20 x 1 (measured). Hence the default 80 x 1.
TEST(Xpbd, UndampedHangingClothNeverGainsEnergyAtTheFrameStep) {
  ClothParams p = testing::small_cloth(8, 8);
  p.origin = Vec3(-0.07, 1.4, 0.0);
  p.row_dir = Vec3(0.0, 0.0, 1.0);
  p.particle_mass = 6e-5;
  p.k_structural = p.k_shear = 50.0;
  p.k_bending = 0.0;
  ClothSystem s(build_cloth(p), nullptr, ForceParams{});
  s.constraints().fix_at(0, s.cloth().rest_positions.segment<3>(0));
  s.constraints().fix_at(7, s.cloth().rest_positions.segment<3>(21));
  const Eigen::VectorXd y0 = s.initial_state(0.0);
  const auto energy = [&](const Eigen::VectorXd& y) {
    return s.energy(y.head(192), y.tail(192)).total();
  };
  const double e0 = energy(y0);
  for (auto [substeps, iterations] : {std::pair{80L, 1L}, {20L, 4L}}) {
    auto method = make_integrator(xpbd_options(1.0 / 30.0, substeps, iterations), s);
    method->reset(0.0, y0);
    double highest = -1.0, lowest = 1.0;
    while (method->time() < 5.0 - 1e-12) {
      method->step(5.0);
      highest = std::max(highest, energy(method->state()) - e0);
      lowest = std::min(lowest, energy(method->state()) - e0);
    }
    EXPECT_LT(highest, 0.0) << substeps << " x " << iterations;
    EXPECT_LT(lowest, -1e-3) << "the cloth fell and swung";
  }
}

TEST(Xpbd, FixedAndMovingParticlesFollowTheirPaths) {
  const testing::CirclingCorner corner = testing::circling_corner();
  auto method = make_integrator(xpbd_options(1e-2, 20, 2), *corner.system);
  testing::expect_fixed_particles_follow(*method, corner, 0.3);
  const IntegratorCounters& c = method->counters();
  EXPECT_EQ(c.steps, 30);
  EXPECT_EQ(c.newton_iters, 30 * 20 * 2);
  EXPECT_EQ(c.rhs_evals, 30 * 20 * 2);
  EXPECT_EQ(c.jacobian_setups, 0);
}

std::string options_error(const nlohmann::json& extra) {
  nlohmann::json o = {{"name", "xpbd"}, {"dt", 1.0 / 30.0}};
  o.update(extra);
  return testing::input_error_message(
      [&] { read_integrator_options(o, "scene.json", "integrator"); });
}

TEST(Xpbd, BadKeysNameTheField) {
  EXPECT_NE(options_error({{"substep", 5}}).find("integrator.substep"), std::string::npos);
  for (const long bad : {0L, 10001L})
    EXPECT_NE(options_error({{"substeps", bad}}).find("integrator.substeps"), std::string::npos)
        << bad;
  EXPECT_NE(options_error({{"substeps", 2.5}}).find("integrator.substeps"), std::string::npos);
  EXPECT_NE(options_error({{"iterations", 0}}).find("integrator.iterations"), std::string::npos);
  EXPECT_NE(options_error({{"sweep", "sor"}}).find("integrator.sweep"), std::string::npos);
  EXPECT_EQ(options_error({{"substeps", 10000}, {"iterations", 3}, {"sweep", "jacobi"}}),
            "no error");
  const IntegratorOptions defaults =
      read_integrator_options({{"name", "xpbd"}, {"dt", 0.01}}, "scene.json", "integrator");
  EXPECT_EQ(defaults.setting_integer("substeps", xpbd_declaration().keys), 80);
  EXPECT_EQ(defaults.setting_integer("iterations", xpbd_declaration().keys), 1);
  EXPECT_EQ(defaults.setting_choice("sweep", xpbd_declaration().keys), "gauss-seidel");
  EXPECT_EQ(find_integrator("xpbd")->family, "position-based");
}

// Gauss-Seidel visits the springs in their colour order and nothing else decides the result:
// two integrators, and one reset to the start, give the same bits (with contact).
TEST(Xpbd, GaussSeidelIsDeterministic) {
  auto s = testing::cloth_against_sphere(CollisionModel::smooth);
  const Eigen::VectorXd y0 = s->initial_state(0.0);
  const Eigen::VectorXd first = run(*s, xpbd_options(1.0 / 30.0, 20, 1), y0, 0.5);
  auto method = make_integrator(xpbd_options(1.0 / 30.0, 20, 1), *s);
  for (int repeat = 0; repeat < 2; ++repeat) {
    method->reset(0.0, y0);
    EXPECT_EQ(testing::run_until(*method, 0.5), first) << repeat;
  }
  EXPECT_GT(position_distance(first, y0), 1e-3);
}

}  // namespace
}  // namespace drape
