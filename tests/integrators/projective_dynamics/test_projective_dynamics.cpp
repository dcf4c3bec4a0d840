// Projective Dynamics: its iterations converge to converged backward Euler (contact and damping
// included), never raise the incremental potential, settle on the Newton equilibrium, keep the
// undamped cloth's energy below its start, refactor exactly when the fixed set changes, and
// refuse bad keys.
#include <gtest/gtest.h>

#include "integrators/implicit_euler/implicit_euler.hpp"
#include "integrators/registry/options_reader.hpp"
#include "integrators/projective_dynamics/projective_dynamics.hpp"
#include "tests/support/backward_euler_reference.hpp"
#include "tests/support/swinging_sheet.hpp"
#include "tests/support/test_support.hpp"

namespace drape {
namespace {

constexpr double frame = 1.0 / 30.0;

IntegratorOptions pd_options(long iterations, bool chebyshev = false, double rho = 0.9) {
  IntegratorOptions o;
  o.name = "projective-dynamics";
  o.dt = frame;
  o.settings = {{"iterations", iterations}, {"chebyshev", chebyshev}, {"rho", rho}};
  return o;
}

Eigen::VectorXd pd_step(ClothSystem& s, const Eigen::VectorXd& y, long iterations) {
  ProjectiveDynamics pd(s, pd_options(iterations));
  pd.reset(0.0, y);
  pd.step(frame);
  return pd.state();
}

// Largest particle distance between the positions of two states.
double distance(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  const Eigen::Index n3 = a.size() / 2;
  double largest = 0.0;
  for (Eigen::Index i = 0; i < n3 / 3; ++i)
    largest = std::max(largest, (a.segment<3>(3 * i) - b.segment<3>(3 * i)).norm());
  return largest;
}

// The distance to backward Euler falls with the iterations and ends below 1e-6 m.
void expect_converges_to_backward_euler(ClothSystem& s, const Eigen::VectorXd& y) {
  const Eigen::VectorXd reference = testing::backward_euler_step(s, y, frame, 1e-10, 1e-12);
  double last = distance(y, reference);
  ASSERT_GT(last, 1e-3) << "the step must move the cloth";
  for (const long iterations : {10, 100, 1000, 30000}) {
    const double d = distance(pd_step(s, y, iterations), reference);
    EXPECT_LT(d, last) << iterations;
    last = d;
  }
  EXPECT_LT(last, 1e-6);
}

TEST(ProjectiveDynamics, ConvergesToBackwardEulerOnTheSwingingSheet) {
  // Damping on: air damping is exact in A, spring damping exact in the gradient.
  auto s = testing::swinging_sheet(1.0);
  Eigen::VectorXd y = s->initial_state(0.0);
  expect_converges_to_backward_euler(*s, y);
  // And from a swinging state, a few backward Euler steps later.
  for (int k = 0; k < 5; ++k) y = testing::backward_euler_step(*s, y, frame, 1e-10, 1e-12);
  expect_converges_to_backward_euler(*s, y);
}

TEST(ProjectiveDynamics, ConvergesToBackwardEulerOnASphereWithTheSmoothAndSurfaceModels) {
  // The particle model's force jumps where the nearest object particle switches: its backward
  // Euler step has no exact root in general (docs/integrators/projective-dynamics.md, Limits).
  for (const CollisionModel model : {CollisionModel::smooth, CollisionModel::surface}) {
    auto s = testing::cloth_against_sphere(model);
    const Eigen::VectorXd y = s->initial_state(0.0);
    int in_contact = 0;
    for (int i = 0; i < s->num_particles(); ++i)
      in_contact += s->collision().energy(i, y.segment<3>(3 * i)) > 0.0;
    ASSERT_GT(in_contact, 0) << "the cloth must touch the sphere";
    expect_converges_to_backward_euler(*s, y);
  }
}

TEST(ProjectiveDynamics, ChebyshevReachesBackwardEulerInAThirtiethOfTheIterations) {
  // Wang (2015): with rho near the plain iteration's contraction (about 1 - 1.5e-4 per
  // iteration on the sheet), 1000 accelerated iterations get below 1e-6 m, where 1000 plain ones
  // stay above 1e-4 m and 30000 are needed.
  auto sheet = testing::swinging_sheet(1.0);
  auto sphere = testing::cloth_against_sphere(CollisionModel::smooth);
  for (ClothSystem* s : {sheet.get(), sphere.get()}) {
    const Eigen::VectorXd y = s->initial_state(0.0);
    const Eigen::VectorXd reference = testing::backward_euler_step(*s, y, frame, 1e-10, 1e-12);
    EXPECT_GT(distance(pd_step(*s, y, 1000), reference), 1e-4);
    ProjectiveDynamics pd(*s, pd_options(1000, true, 0.999));
    pd.reset(0.0, y);
    pd.step(frame);
    EXPECT_LT(distance(pd.state(), reference), 1e-6);
  }
}

// The swinging sheet without spring damping (whose direction turns with x: not a potential).
std::unique_ptr<ClothSystem> undamped_springs_sheet() {
  ClothParams p = testing::swinging_sheet(1.0)->cloth().params;
  p.damping_spring = 0.0;
  auto s = std::make_unique<ClothSystem>(build_cloth(p), nullptr, ForceParams{});
  const Eigen::VectorXd& rest = s->cloth().rest_positions;
  s->constraints().fix_at(0, rest.segment<3>(0));
  s->constraints().fix_at(p.cols - 1, rest.segment<3>(3 * (p.cols - 1)));
  return s;
}

TEST(ProjectiveDynamics, IncrementalPotentialNeverRisesBetweenIterations) {
  auto s = undamped_springs_sheet();
  ProjectiveDynamics pd(*s, pd_options(20));
  pd.record_potential(true);
  pd.reset(0.0, s->initial_state(0.0));
  for (int step = 0; step < 10; ++step) {
    pd.step(1.0);
    const std::vector<double>& e = pd.potential_trace();
    ASSERT_EQ(e.size(), 21u);
    EXPECT_LT(e.back(), e.front()) << step;
    for (std::size_t k = 1; k < e.size(); ++k)
      EXPECT_LE(e[k], e[k - 1] + 1e-12 * std::abs(e[k - 1])) << step << " " << k;
  }
}

TEST(ProjectiveDynamics, SettlesOnTheNewtonEquilibrium) {
  // A sheet and a chain (one row pinned at both ends), damped so that they come to rest.
  auto sheet = testing::pinned_test_cloth(0.02, 0.002);
  ClothParams chain_params = testing::small_cloth(1, 9);
  chain_params.damping_spring = 0.02;
  chain_params.damping_air = 0.002;
  auto chain = std::make_unique<ClothSystem>(build_cloth(chain_params), nullptr, ForceParams{});
  chain->constraints().fix_at(0, chain->cloth().rest_positions.segment<3>(0));
  chain->constraints().fix_at(8, chain->cloth().rest_positions.segment<3>(24));
  for (ClothSystem* s : {sheet.get(), chain.get()}) {
    const Eigen::VectorXd expected = testing::newton_equilibrium(*s);
    EXPECT_GT((expected - s->cloth().rest_positions).lpNorm<Eigen::Infinity>(), 0.003);
    ProjectiveDynamics pd(*s, pd_options(10));
    const Eigen::VectorXd x = testing::settle(pd, *s);
    EXPECT_LT((x - expected).lpNorm<Eigen::Infinity>(), 1e-6);
  }
}

TEST(ProjectiveDynamics, UndampedHangingClothNeverGainsEnergyAtTheFrameStep) {
  auto s = testing::pinned_test_cloth();
  ProjectiveDynamics pd(*s, pd_options(10));
  const Eigen::VectorXd y0 = s->initial_state(0.0);
  pd.reset(0.0, y0);
  const auto energy = [&](const Eigen::VectorXd& y) {
    const Eigen::Index n3 = y.size() / 2;
    return s->energy(y.head(n3), y.tail(n3)).total();
  };
  const double start = energy(y0);
  double lowest = start;
  while (pd.time() < 3.0 - 1e-12) {
    pd.step(3.0);
    const double e = energy(pd.state());
    EXPECT_LE(e, start) << pd.time();
    lowest = std::min(lowest, e);
  }
  EXPECT_LT(lowest, start - 1e-4) << "the cloth must fall";
}

TEST(ProjectiveDynamics, RefactorsExactlyWhenTheFixedSetChanges) {
  auto s = testing::swinging_sheet(1.0);
  ProjectiveDynamics pd(*s, pd_options(10));
  pd.reset(0.0, s->initial_state(0.0));
  for (int k = 0; k < 3; ++k) pd.step(1.0);
  EXPECT_EQ(pd.counters().jacobian_setups, 1);
  EXPECT_EQ(pd.counters().newton_iters, 30);
  // An event that keeps the fixed set: no refactorisation.
  pd.reset(pd.time(), pd.state());
  pd.step(1.0);
  EXPECT_EQ(pd.counters().jacobian_setups, 1);
  // A pin released: one refactorisation, and the step of a fresh integrator.
  s->constraints().release(11);
  const Eigen::VectorXd y = pd.state();
  const double t = pd.time();
  pd.reset(t, y);
  pd.step(1.0);
  EXPECT_EQ(pd.counters().jacobian_setups, 2);
  ProjectiveDynamics fresh(*s, pd_options(10));
  fresh.reset(t, y);
  fresh.step(1.0);
  EXPECT_EQ(fresh.counters().jacobian_setups, 1);
  EXPECT_EQ(pd.state(), fresh.state());
  EXPECT_GT(distance(pd.state(), y), 1e-4) << "the released corner must move";
}

std::string error_of(const nlohmann::json& settings) {
  nlohmann::json o = {{"name", "projective-dynamics"}, {"dt", frame}};
  for (const auto& [key, value] : settings.items()) o[key] = value;
  return testing::input_error_message(
      [&] { read_integrator_options(o, "scene.json", "integrator"); });
}

TEST(ProjectiveDynamics, RefusesBadKeysNamingTheField) {
  EXPECT_EQ(error_of(nlohmann::json::object()), "no error");
  EXPECT_EQ(error_of({{"iterations", 100}, {"chebyshev", true}, {"rho", 0.5}}), "no error");
  for (const nlohmann::json& bad : {nlohmann::json{{"iterations", 0}},
                                    nlohmann::json{{"iterations", 100001}},
                                    nlohmann::json{{"iterations", 2.5}}})
    EXPECT_NE(error_of(bad).find("integrator.iterations"), std::string::npos) << bad;
  for (const double rho : {0.0, 1.0, -0.5, 1.5})
    EXPECT_NE(error_of({{"rho", rho}}).find("integrator.rho"), std::string::npos) << rho;
  EXPECT_NE(error_of({{"chebyshev", 1}}).find("integrator.chebyshev"), std::string::npos);
  EXPECT_NE(error_of({{"iteration", 10}}).find("integrator.iteration"), std::string::npos);
}

}  // namespace
}  // namespace drape
