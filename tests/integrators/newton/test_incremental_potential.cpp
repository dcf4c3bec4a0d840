// The incremental potential of an implicit stage: its gradient is the stage residual and the
// derivative of its value; the gradient's derivative is M - gamma D - gamma^2 K.
#include <gtest/gtest.h>

#include "integrators/newton/incremental_potential.hpp"
#include "tests/support/test_support.hpp"

namespace drape {
namespace {

struct Stage {
  std::unique_ptr<ClothSystem> system;
  Eigen::VectorXd a, z;
  double t = 0.0, gamma = 0.02;
};

// A cloth (by default the damped pinned one, no object) with a known part a and an iterate z,
// both shaken.
Stage shaken_stage(ForceSplit split, IncrementalPotential*& potential,
                   std::unique_ptr<IncrementalPotential>& owner,
                   std::unique_ptr<ClothSystem> system = testing::pinned_test_cloth(0.05, 0.01)) {
  Stage s;
  s.system = std::move(system);
  s.a = testing::jitter(s.system->initial_state(0.0), 0.003, 3);
  s.z = s.a;
  owner = std::make_unique<IncrementalPotential>(*s.system, split);
  potential = owner.get();
  potential->begin_stage(s.t, s.gamma, s.a, s.z);
  const Eigen::Index n3 = s.z.size() / 2;
  const Eigen::VectorXd v = testing::jitter(s.z.tail(n3), 0.2, 4);
  potential->state_of(v, s.z);
  potential->freeze_damping(s.z);
  return s;
}

// The implicit sides of the splits, without an object and, with the contact implicit
// (arkode-dirk's `all`, arkode-imex's springs+collision), on a sphere with the smooth model;
// and arkode-dirk's and arkode-imex's with the smooth Coulomb force (mu = 0.4, docs/friction.md),
// whose dissipation the value holds with the contact forces frozen at the iterate.
struct SplitCase {
  ForceSplit split;
  bool contact;
  double friction = 0.0;
};
constexpr ForceSplit with_friction(ForceSplit split) {
  split.with_smooth_friction = true;
  return split;
}
const SplitCase split_cases[] = {{ForceSplit::all, false},
                                 {ForceSplit::springs, false},
                                 {ForceSplit::all, true},
                                 {ForceSplit::springs_and_collision, true},
                                 {with_friction(ForceSplit::all), true, 0.4},
                                 {with_friction(ForceSplit::springs), true, 0.4}};

Stage stage_of(const SplitCase& c, IncrementalPotential*& potential,
               std::unique_ptr<IncrementalPotential>& owner) {
  if (!c.contact) return shaken_stage(c.split, potential, owner);
  Stage s = shaken_stage(c.split, potential, owner,
                         testing::cloth_against_sphere(CollisionModel::smooth, c.friction));
  const Eigen::Index n3 = s.z.size() / 2;
  EXPECT_GT(s.system->energy(s.z.head(n3), s.z.tail(n3)).collision, 0.0) << "in contact";
  return s;
}

TEST(IncrementalPotential, GradientIsTheStageResidual) {
  for (const SplitCase& c : split_cases) {
    IncrementalPotential* p = nullptr;
    std::unique_ptr<IncrementalPotential> owner;
    Stage s = stage_of(c, p, owner);
    const ForceSplit split = c.split;
    const Eigen::Index n3 = s.z.size() / 2;
    // ARKODE's residual z - a - gamma f_I(t, z): zero in x by the elimination, M^-1 g in v.
    Eigen::VectorXd f(s.z.size());
    s.system->rhs(s.t, s.z, f, split);
    const Eigen::VectorXd residual = s.z - s.a - s.gamma * f;
    Eigen::VectorXd g(n3);
    p->gradient(s.z, g);
    EXPECT_LT(residual.head(n3).lpNorm<Eigen::Infinity>(), 1e-15);
    EXPECT_LT((s.system->particle_mass() * residual.tail(n3) - g).lpNorm<Eigen::Infinity>(),
              1e-12 * g.lpNorm<Eigen::Infinity>());
  }
}

TEST(IncrementalPotential, GradientIsTheDerivativeOfTheValue) {
  for (const SplitCase& c : split_cases) {
    IncrementalPotential* p = nullptr;
    std::unique_ptr<IncrementalPotential> owner;
    Stage s = stage_of(c, p, owner);
    const Eigen::Index n3 = s.z.size() / 2;
    Eigen::VectorXd trial = s.z;
    const auto value = [&](const Eigen::VectorXd& v) {
      p->state_of(v, trial);
      return p->value(trial);
    };
    Eigen::VectorXd expected = testing::fd_gradient(value, s.z.tail(n3), 1e-6);
    s.system->constraints().zero_fixed(expected);
    Eigen::VectorXd g(n3);
    p->gradient(s.z, g);
    EXPECT_LT((g - expected).lpNorm<Eigen::Infinity>(), 1e-7 * g.lpNorm<Eigen::Infinity>());
  }
}

TEST(IncrementalPotential, GradientDerivativeIsTheNewtonMatrix) {
  IncrementalPotential* p = nullptr;
  std::unique_ptr<IncrementalPotential> owner;
  Stage s = shaken_stage(ForceSplit::all, p, owner);
  const Eigen::Index n3 = s.z.size() / 2;
  Eigen::VectorXd w = testing::jitter(Eigen::VectorXd::Zero(n3), 1.0, 5);
  s.system->constraints().zero_fixed(w);
  // d g / dv w = M w - gamma (K gamma w + D w) with the exact Jacobian.
  Eigen::VectorXd jw(n3);
  s.system->force_jacobian_times(s.z.head(n3), s.z.tail(n3), s.gamma * w, w, jw, false);
  const Eigen::VectorXd expected = s.system->particle_mass() * w - s.gamma * jw;
  const double h = 1e-6;
  Eigen::VectorXd plus = s.z, minus = s.z, g_plus(n3), g_minus(n3);
  p->state_of(s.z.tail(n3) + h * w, plus);
  p->state_of(s.z.tail(n3) - h * w, minus);
  p->gradient(plus, g_plus);
  p->gradient(minus, g_minus);
  const Eigen::VectorXd fd = (g_plus - g_minus) / (2 * h);
  EXPECT_LT((fd - expected).lpNorm<Eigen::Infinity>(), 1e-6 * expected.lpNorm<Eigen::Infinity>());
}

TEST(IncrementalPotential, FixedParticlesTakeTheirStageValues) {
  IncrementalPotential* p = nullptr;
  std::unique_ptr<IncrementalPotential> owner;
  Stage s = shaken_stage(ForceSplit::all, p, owner);
  Eigen::VectorXd f(s.z.size());
  s.system->rhs(s.t, s.z, f);
  const Eigen::Index n3 = s.z.size() / 2;
  for (const int i : s.system->constraints().fixed_particles()) {
    EXPECT_EQ(s.z.segment<3>(3 * i), s.a.segment<3>(3 * i) + s.gamma * f.segment<3>(3 * i));
    EXPECT_EQ(s.z.segment<3>(n3 + 3 * i),
              s.a.segment<3>(n3 + 3 * i) + s.gamma * f.segment<3>(n3 + 3 * i));
  }
}

}  // namespace
}  // namespace drape
