// The counters potential_decrease and potential_rises (integrator.hpp, docs/outputs.md) of the
// methods that minimise backward Euler's incremental potential, against the potential evaluated
// here at each step's start guess and end: VBD's G in positions (vertex_block_potential.hpp) and
// the Newton's E in velocities (incremental_potential.hpp), each checked against the other and
// against the counter of every method, BDF2's own stage potential for converged bdf2.
#include <gtest/gtest.h>

#include <functional>

#include "integrators/registry/options_reader.hpp"
#include "integrators/registry/registry.hpp"
#include "integrators/newton/incremental_potential.hpp"
#include "integrators/vbd/vertex_block_potential.hpp"
#include "tests/support/swinging_sheet.hpp"

namespace drape {
namespace {

constexpr double h = 1.0 / 30.0;
constexpr int steps = 10;

std::unique_ptr<Integrator> method_named(ClothSystem& s, const nlohmann::json& options) {
  nlohmann::json o = options;
  o["dt"] = h;
  return make_integrator(read_integrator_options(o, "test", "integrator"), s);
}

// E of the stage y' = a + gamma f(t, y') at the guess `start` (its velocities; positions
// a_x + gamma v, as the stage sets them) minus E at the stage's solution `end`.
double stage_decrease(const ClothSystem& s, double t, double gamma, const Eigen::VectorXd& a,
                      const Eigen::VectorXd& start, const Eigen::VectorXd& end) {
  IncrementalPotential e(s, ForceSplit::all);
  Eigen::VectorXd z = start;
  e.begin_stage(t, gamma, a, z);
  return e.value(z) - e.value(end);
}

// Backward Euler's potential from the start x_n + h v_n to the end's positions, as G in
// positions and as E in velocities (v = (x - x_n) / h); the two must agree.
double backward_euler_decrease(const ClothSystem& s, double t, const Eigen::VectorXd& before,
                               const Eigen::VectorXd& after) {
  const Eigen::Index n3 = before.size() / 2;
  VertexBlockPotential g(s);
  g.begin_step(h, before.head(n3), before.tail(n3));
  const Eigen::VectorXd start = before.head(n3) + h * before.tail(n3);
  const double in_positions = g.value(start) - g.value(after.head(n3));
  Eigen::VectorXd end = after;
  end.tail(n3) = (after.head(n3) - before.head(n3)) / h;
  const double in_velocities = stage_decrease(s, t, h, before, before, end);
  EXPECT_NEAR(in_positions, in_velocities, 1e-10 * std::abs(in_velocities));
  return in_velocities;
}

// Runs `method` from the sheet at rest for `steps` steps, adding up the decrease `decrease`
// computes from the states before and after each step (and the one before those); compares the
// sum with the counter.
void expect_counted(ClothSystem& s, Integrator& method,
                    const std::function<double(int, const Eigen::VectorXd&, const Eigen::VectorXd&,
                                               const Eigen::VectorXd&)>& decrease,
                    const std::string& name) {
  Eigen::VectorXd older, before = s.initial_state(0.0);
  method.reset(0.0, before);
  double expected = 0.0;
  for (int k = 0; k < steps; ++k) {
    method.step(1.0);
    expected += decrease(k, older, before, method.state());
    older = before;
    before = method.state();
  }
  const IntegratorCounters& c = method.counters();
  EXPECT_GT(expected, 0.0) << name;
  EXPECT_NEAR(c.potential_decrease, expected, 1e-9 * expected) << name;
  EXPECT_EQ(c.potential_rises, 0) << name;
  EXPECT_EQ(c.step_halvings, 0) << name;
}

// Without spring damping (whose frozen directions would make E a function of the iterate) PD,
// VBD and converged implicit-euler lower backward Euler's potential at every step, by what the
// counter says; so does converged bdf2 its own stage's.
TEST(PotentialCounters, EqualTheDecreaseOfThePotentialEvaluatedIndependently) {
  auto s = testing::swinging_sheet(1.0, 12, 0.0);
  const auto backward_euler = [&](int k, const Eigen::VectorXd&, const Eigen::VectorXd& before,
                                  const Eigen::VectorXd& after) {
    return backward_euler_decrease(*s, (k + 1) * h, before, after);
  };
  for (const nlohmann::json& options :
       {nlohmann::json{{"name", "projective-dynamics"}}, nlohmann::json{{"name", "vbd"}},
        nlohmann::json{{"name", "implicit-euler"}, {"solve", "converged"}}}) {
    auto method = method_named(*s, options);
    expect_counted(*s, *method, backward_euler, options.dump());
  }
  // BDF2: y' = 4/3 y_n - 1/3 y_{n-1} + 2/3 h f(y'), started by backward Euler; the guess y_n.
  auto bdf2 = method_named(*s, {{"name", "bdf2"}, {"solve", "converged"}});
  expect_counted(
      *s, *bdf2,
      [&](int k, const Eigen::VectorXd& older, const Eigen::VectorXd& before,
          const Eigen::VectorXd& after) {
        if (k == 0) return stage_decrease(*s, h, h, before, before, after);
        const Eigen::VectorXd a = (4.0 * before - older) / 3.0;
        return stage_decrease(*s, (k + 1) * h, 2.0 * h / 3.0, a, before, after);
      },
      "bdf2");
}

// The methods that do not minimise it report nothing.
TEST(PotentialCounters, AreZeroForTheOtherMethods) {
  auto s = testing::swinging_sheet(1.0, 12, 0.0);
  for (const char* name : {"leapfrog", "implicit-euler", "bdf2", "xpbd", "arkode-erk"}) {
    auto method = method_named(*s, {{"name", name}});
    method->reset(0.0, s->initial_state(0.0));
    method->step(h);
    EXPECT_EQ(method->counters().potential_decrease, 0.0) << name;
    EXPECT_EQ(method->counters().potential_rises, 0) << name;
  }
}

}  // namespace
}  // namespace drape
