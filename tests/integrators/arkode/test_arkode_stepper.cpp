// ARKODE explicit, implicit and IMEX integrators: orders of accuracy of several tables,
// equilibrium, large stable steps, constraints, resets at events and failures.
#include <gtest/gtest.h>

#include "core/dummy/dummy_sources.hpp"
#include "core/scene/scene.hpp"
#include "integrators/arkode/arkode_stepper.hpp"
#include "integrators/registry/registry.hpp"
#include "tests/support/test_support.hpp"

namespace drape {
namespace {

IntegratorOptions arkode_options(const std::string& name, const std::string& table, double dt) {
  IntegratorOptions o;
  o.name = name;
  o.table = table;
  o.dt = dt;
  // Tight tolerances: in fixed-step runs they set Newton's stopping test, which must stay far
  // below the truncation errors being measured.
  o.rtol = 1e-12;
  o.atol = 1e-14;
  validate_integrator_choice(o, "test", "integrator");
  return o;
}

Eigen::VectorXd run(ClothSystem& s, const IntegratorOptions& o, const Eigen::VectorXd& y0,
                    double t_end) {
  auto method = make_integrator(o, s);
  method->reset(0.0, y0);
  return testing::run_until(*method, t_end);
}

struct OrderCase {
  const char* integrator;
  const char* table;
  int order;
  double dt0;  // largest step, in the asymptotic range
  bool damped; // air damping gives IMEX a state-dependent explicit part
};

class ArkodeOrder : public ::testing::TestWithParam<OrderCase> {};

TEST_P(ArkodeOrder, FixedStepErrorHasTheTableOrder) {
  const OrderCase c = GetParam();
  auto s = testing::pinned_test_cloth(0.0, c.damped ? 0.005 : 0.0);
  const Eigen::VectorXd y0 = testing::shaken_state(*s);
  const double t_end = 0.05;
  // An independent order-8 reference with a step far below the ones measured.
  const Eigen::VectorXd reference =
      run(*s, arkode_options("arkode-erk", "ARKODE_FEHLBERG_13_7_8", 2.5e-5), y0, t_end);
  std::vector<double> dts, errors;
  for (int k = 0; k < 4; ++k) {
    dts.push_back(c.dt0 / (1 << k));
    const Eigen::VectorXd y = run(*s, arkode_options(c.integrator, c.table, dts.back()), y0, t_end);
    errors.push_back((y - reference).head(y.size() / 2).norm());
  }
  EXPECT_NEAR(testing::fitted_order(dts, errors), c.order, 0.3)
      << c.table << " errors " << errors[0] << " " << errors[1] << " " << errors[2] << " "
      << errors[3];
}

INSTANTIATE_TEST_SUITE_P(
    Tables, ArkodeOrder,
    ::testing::Values(
        OrderCase{"arkode-erk", "ARKODE_BOGACKI_SHAMPINE_4_2_3", 3, 1e-3, false},
        // ERKStep 6.4.1 gets this one wrong (last node 1, last row not b): ARKStep must not.
        OrderCase{"arkode-erk", "ARKODE_ARK436L2SA_ERK_6_3_4", 4, 1e-3, false},
        OrderCase{"arkode-erk", "ARKODE_DORMAND_PRINCE_7_4_5", 5, 2e-3, false},
        OrderCase{"arkode-dirk", "ARKODE_SDIRK_2_1_2", 2, 1e-3, false},
        OrderCase{"arkode-dirk", "ARKODE_ARK324L2SA_DIRK_4_2_3", 3, 1e-3, false},
        OrderCase{"arkode-dirk", "ARKODE_ESDIRK436L2SA_6_3_4", 4, 2e-3, false},
        OrderCase{"arkode-dirk", "ARKODE_ESDIRK437L2SA_7_3_4", 4, 2e-3, false},
        OrderCase{"arkode-dirk", "ARKODE_ESDIRK547L2SA_7_4_5", 5, 4e-3, false},
        OrderCase{"arkode-imex", "ARKODE_ARK324L2SA_4_2_3", 3, 1e-3, true},
        OrderCase{"arkode-imex", "ARKODE_ARK436L2SA_6_3_4", 4, 2e-3, true}),
    [](const auto& test) { return std::string(test.param.table).substr(7); });

// Every ARKODE integrator settles the damped pinned cloth on Newton's equilibrium; the implicit
// ones with a step several times leap-frog's measured stability limit.
TEST(ArkodeStepper, SettlesOnTheNewtonEquilibrium) {
  auto s = testing::pinned_test_cloth(0.02, 0.002);
  const Eigen::VectorXd expected = testing::newton_equilibrium(*s);
  const double limit = testing::leapfrog_stability_limit(*s, s->initial_state(0.0));
  EXPECT_GT(limit, 1e-4);
  struct Case { const char* name; double dt; };
  for (const Case c : {Case{"arkode-erk", 0.5 * limit}, Case{"arkode-dirk", 5.0 * limit},
                       Case{"arkode-imex", 5.0 * limit}}) {
    IntegratorOptions o = arkode_options(c.name, "", c.dt);
    o.rtol = 1e-10;
    auto method = make_integrator(o, *s);
    const Eigen::VectorXd x = testing::settle(*method, *s);
    EXPECT_LT((x - expected).lpNorm<Eigen::Infinity>(), 1e-8) << c.name << " dt " << c.dt;
  }
}

// A cloth released from the rest grid falls and swings under gravity. (From a randomly shaken
// grid, many springs start compressed: their buckling modes grow faster than 1/h at such
// steps and Newton's method on the stage equations diverges; implicit-euler takes only one
// linearised step and does not notice.)
TEST(ArkodeStepper, ImplicitStepFarBeyondTheExplicitLimitStaysBounded) {
  auto s = testing::pinned_test_cloth();
  const Eigen::VectorXd y0 = s->initial_state(0.0);
  const double limit = testing::leapfrog_stability_limit(*s, y0);
  const Eigen::Index n3 = 3 * s->num_particles();
  for (const char* name : {"arkode-dirk", "arkode-imex"}) {
    // Default tolerances: a 1e-12 Newton test is below the round-off of these forces at
    // such steps.
    IntegratorOptions o = arkode_options(name, "", 10.0 * limit);
    o.rtol = IntegratorOptions{}.rtol;
    o.atol = IntegratorOptions{}.atol;
    const Eigen::VectorXd y = run(*s, o, y0, 0.5);
    EXPECT_LT((y.head(n3) - y0.head(n3)).lpNorm<Eigen::Infinity>(), 0.1) << name;
  }
}

TEST(ArkodeStepper, FixedAndMovingParticlesFollowTheirPaths) {
  for (const char* name : {"arkode-erk", "arkode-dirk", "arkode-imex"}) {
    for (const bool adaptive : {false, true}) {
      SCOPED_TRACE(std::string(name) + (adaptive ? " adaptive" : " fixed"));
      const testing::CirclingCorner c = testing::circling_corner();
      IntegratorOptions o = arkode_options(name, "", 1e-3);
      o.adaptive = adaptive;
      o.rtol = 1e-6;
      o.atol = 1e-9;
      auto method = make_integrator(o, *c.system);
      testing::expect_fixed_particles_follow(*method, c, 0.3);
    }
  }
}

// A release in the middle of an adaptive run continues exactly as a run started at the release
// state: reset() leaves no history or stale Jacobian behind.
TEST(ArkodeStepper, ReleaseMidRunMatchesAFreshStart) {
  for (const char* name : {"arkode-erk", "arkode-dirk", "arkode-imex"}) {
    IntegratorOptions o = arkode_options(name, "", 1e-4);
    o.adaptive = true;
    o.rtol = 1e-8;
    o.atol = 1e-10;
    auto s = testing::pinned_test_cloth(0.01, 0.001);
    auto method = make_integrator(o, *s);
    method->reset(0.0, testing::shaken_state(*s));
    testing::run_until(*method, 0.1);
    const Eigen::VectorXd at_release = method->state();
    s->constraints().release(3);
    method->reset(0.1, at_release);
    const Eigen::VectorXd continued = testing::run_until(*method, 0.2);
    EXPECT_GT((continued - at_release).head(48).norm(), 1e-3) << "the corner falls";

    auto fresh_system = testing::pinned_test_cloth(0.01, 0.001);
    fresh_system->constraints().release(3);
    auto fresh = make_integrator(o, *fresh_system);
    fresh->reset(0.1, at_release);
    const Eigen::VectorXd expected = testing::run_until(*fresh, 0.2);
    EXPECT_LT((continued - expected).norm(), 1e-12) << name;
  }
}

TEST(ArkodeStepper, CountersAddUp) {
  auto s = testing::pinned_test_cloth(0.01, 0.001);
  IntegratorOptions o = arkode_options("arkode-dirk", "ARKODE_SDIRK_2_1_2", 1e-2);
  o.rtol = 1e-6;
  auto method = make_integrator(o, *s);
  method->reset(0.0, s->initial_state(0.0));
  testing::run_until(*method, 0.1);
  const IntegratorCounters& c = method->counters();
  EXPECT_EQ(c.steps, 10);
  EXPECT_EQ(c.attempts, 10);
  EXPECT_GE(c.newton_iters, 20);  // two implicit stages a step
  EXPECT_GT(c.linear_iters, 0);
  EXPECT_GT(c.jacobian_setups, 0);
  EXPECT_GT(c.rhs_evals, 0);
  EXPECT_EQ(c.resets, 0) << "the start is not a restart";
}

// The cloth of experiments/scenes/drape_dress_form.json, pinned, at its start: 7 particles
// already within the collision threshold of the chest.
std::unique_ptr<ClothSystem> drape_scene_cloth(CollisionModel model = CollisionModel::particle) {
  Scene scene =
      load_scene(std::string(DRAPE_SOURCE_DIR) + "/experiments/scenes/drape_dress_form.json");
  scene.forces.collision.model = model;
  auto dummy = std::make_shared<const Dummy>(
      make_dummy(scene.dummy, scene.file, "dummy", scene.base_dir));
  auto s = std::make_unique<ClothSystem>(build_cloth(scene.cloth), dummy, scene.forces);
  for (const GridPoint& pin : scene.pins) {
    const int i = s->cloth().index(pin.row, pin.col);
    s->constraints().fix_at(i, s->cloth().rest_positions.segment<3>(3 * i));
  }
  return s;
}

// These runs stopped with ARK_CONV_FAILURE before t = 2 ms of the drape scene: Newton's
// iterates went back and forth across the switch of a particle's nearest object particle, or
// across an edge of the interpolated surface (surface model). With the contact set fixed over
// each step (Collision::pair_contacts) they run through, and after every step the pairs are
// the nearest object particles of the new state.
TEST(ArkodeStepper, DirkRunsThroughContactWithTheContactSetOfTheStepStart) {
  struct Case { const char* table; CollisionModel model; };
  for (const Case c : {Case{"ARKODE_SDIRK_2_1_2", CollisionModel::particle},
                       Case{"ARKODE_KVAERNO_4_2_3", CollisionModel::particle},
                       Case{"ARKODE_ARK324L2SA_DIRK_4_2_3", CollisionModel::surface}}) {
    SCOPED_TRACE(c.table);
    auto s = drape_scene_cloth(c.model);
    IntegratorOptions o = arkode_options("arkode-dirk", c.table, 2e-4);
    o.rtol = IntegratorOptions{}.rtol;
    o.atol = IntegratorOptions{}.atol;
    auto method = make_integrator(o, *s);
    const Eigen::VectorXd y0 = s->initial_state(0.0);
    method->reset(0.0, y0);
    const double radius = 2.0 * s->params().collision.threshold;
    const Eigen::Index n3 = 3 * s->num_particles();
    int in_contact = 0;
    while (method->time() < 0.004 - 1e-12) {
      method->step(0.004);
      const auto x = method->state().head(n3);
      for (int i = 0; i < s->num_particles(); ++i) {
        const Vec3 xi = particle(x, i);
        if (c.model == CollisionModel::particle) {
          ASSERT_EQ(s->collision().paired(i), s->dummy()->nearest_within(xi, radius).index);
        }
        in_contact += s->collision().force(i, xi).norm() > 0.0;
      }
    }
    EXPECT_EQ(method->counters().steps, 20);
    EXPECT_GT(in_contact, 20 * 2) << "particles in contact at every step";
    for (const int i : s->constraints().fixed_particles())
      EXPECT_EQ(particle(method->state().head(n3), i), particle(y0.head(n3), i));
    method.reset();
    EXPECT_EQ(s->collision().paired(0), -1) << "the stepper unpairs when it goes";
  }
}

// arkode-erk and arkode-imex (collision explicit) evaluate the model of docs/model.md: no pairs.
TEST(ArkodeStepper, ExplicitCollisionIsNeverPaired) {
  for (const char* name : {"arkode-erk", "arkode-imex"}) {
    auto s = drape_scene_cloth();
    auto method = make_integrator(arkode_options(name, "", 2e-4), *s);
    method->reset(0.0, s->initial_state(0.0));
    method->step(1.0);
    for (int i = 0; i < s->num_particles(); ++i) ASSERT_EQ(s->collision().paired(i), -1) << name;
  }
}

TEST(ArkodeStepper, SolverFailureIsAnIntegratorFailure) {
  auto s = testing::pinned_test_cloth();
  IntegratorOptions o = arkode_options("arkode-dirk", "", 0.05);
  o.max_newton_iters = 1;
  o.max_step_halvings = 0;  // the first hard stage ends the run
  auto method = make_integrator(o, *s);
  method->reset(0.0, testing::shaken_state(*s));
  try {
    testing::run_until(*method, 1.0);
    FAIL() << "no failure";
  } catch (const IntegratorFailure& failure) {
    EXPECT_EQ(failure.flag(), "ARK_CONV_FAILURE");
    // ARKODE's own explanation travels in the message instead of being printed.
    EXPECT_NE(std::string(failure.what()).find("convergence test failed"), std::string::npos)
        << failure.what();
  }
}

// A fixed step whose Newton solve fails is taken again as two halves (recursively): the run
// goes on, on the same time grid, and ends near a fine-step solution.
TEST(ArkodeStepper, FailedFixedStepIsTakenAgainAsTwoHalves) {
  auto s = testing::pinned_test_cloth();
  const Eigen::VectorXd y0 = testing::shaken_state(*s);
  IntegratorOptions o = arkode_options("arkode-dirk", "ARKODE_SDIRK_2_1_2", 0.05);
  o.rtol = 1e-4;  // the defaults: Newton stops at a fraction of the local error
  o.atol = 1e-7;
  o.max_newton_iters = 2;
  auto method = make_integrator(o, *s);
  method->reset(0.0, y0);
  for (int k = 1; k <= 4; ++k) {
    EXPECT_DOUBLE_EQ(method->step(1.0), 0.05 * k);
    EXPECT_DOUBLE_EQ(method->last_step(), 0.05);
  }
  const IntegratorCounters& c = method->counters();
  EXPECT_GT(c.step_halvings, 0);
  // Every halving follows a failed attempt and puts two steps in the place of one.
  EXPECT_GE(c.steps, 4 + c.step_halvings);
  EXPECT_GE(c.attempts - c.steps, c.step_halvings);
  // As accurate as the same step solved to convergence (10 Newton iterations, no halving).
  o.max_newton_iters = 10;
  const Eigen::VectorXd whole_steps = run(*s, o, y0, 0.2);
  const Eigen::VectorXd fine =
      run(*s, arkode_options("arkode-dirk", "ARKODE_SDIRK_2_1_2", 1e-4), y0, 0.2);
  const Eigen::Index n3 = y0.size() / 2;
  EXPECT_LT((method->state() - fine).head(n3).norm(), (whole_steps - fine).head(n3).norm());
}

TEST(ArkodeStepper, ExhaustedHalvingsNameTheSmallestStep) {
  auto s = testing::pinned_test_cloth();
  IntegratorOptions o = arkode_options("arkode-dirk", "", 0.05);
  o.max_newton_iters = 1;
  o.max_step_halvings = 1;
  auto method = make_integrator(o, *s);
  method->reset(0.0, testing::shaken_state(*s));
  try {
    testing::run_until(*method, 1.0);
    FAIL() << "no failure";
  } catch (const IntegratorFailure& failure) {
    EXPECT_EQ(failure.flag(), "ARK_CONV_FAILURE");
    EXPECT_NE(std::string(failure.what()).find("halved 1 times, to 0.025 s"), std::string::npos)
        << failure.what();
  }
}

// After a run whose halvings ran out, a reset starts again at the fixed step, not at the last
// half that was tried: from the equilibrium, where Newton converges at once, the first
// step after the reset covers dt.
TEST(ArkodeStepper, ResetAfterExhaustedHalvingsStartsAgainAtDt) {
  auto s = testing::pinned_test_cloth(0.02, 0.002);
  IntegratorOptions settling = arkode_options("arkode-dirk", "", 0.01);
  Eigen::VectorXd equilibrium = Eigen::VectorXd::Zero(s->size());
  equilibrium.head(3 * s->num_particles()) = testing::settle(*make_integrator(settling, *s), *s);
  IntegratorOptions o = arkode_options("arkode-dirk", "", 0.05);
  // ARKODE's Newton: two of its iterations solve the stage from the equilibrium, while the
  // line search's first, definite directions converge only linearly
  // (docs/integrators/line-search-newton.md).
  o.nonlinear_solver = "newton";
  o.max_newton_iters = 2;  // too few for the shaken start, even at dt / 8
  o.max_step_halvings = 3;
  auto method = make_integrator(o, *s);
  method->reset(0.0, testing::shaken_state(*s));
  EXPECT_THROW(testing::run_until(*method, 1.0), IntegratorFailure);
  method->reset(0.0, equilibrium);
  EXPECT_DOUBLE_EQ(method->step(1.0), 0.05);
  EXPECT_EQ(method->counters().step_halvings, 3);  // the first run's only
}

// Halved steps count against max_steps inside one step() call: a step that would need 2^10
// attempts stops at the bound.
TEST(ArkodeStepper, HalvedStepsStopAtMaxSteps) {
  auto s = testing::pinned_test_cloth();
  IntegratorOptions o = arkode_options("arkode-dirk", "", 0.05);
  o.max_newton_iters = 1;
  o.max_step_halvings = 10;
  o.max_steps = 6;
  auto method = make_integrator(o, *s);
  method->reset(0.0, testing::shaken_state(*s));
  try {
    method->step(1.0);
    FAIL() << "no failure";
  } catch (const IntegratorFailure& failure) {
    EXPECT_EQ(failure.flag(), "max_steps");
    EXPECT_EQ(method->counters().attempts, 6);
  }
}

// A stop time within round-off beyond one step is reached in that step, exactly (ARKODE alone
// would stop at t + dt and leave a sliver for the next call).
TEST(ArkodeStepper, FixedStepLandsExactlyOnAStopTimeJustBeyondDt) {
  auto s = testing::pinned_test_cloth();
  for (const char* name : {"arkode-erk", "arkode-dirk"}) {
    auto method = make_integrator(arkode_options(name, "", 1e-3), *s);
    method->reset(0.0, s->initial_state(0.0));
    const double t_stop = 1e-3 * (1.0 + 1e-10);
    EXPECT_EQ(method->step(t_stop), t_stop) << name;
    EXPECT_EQ(method->counters().steps, 1) << name;
  }
}

}  // namespace
}  // namespace drape
