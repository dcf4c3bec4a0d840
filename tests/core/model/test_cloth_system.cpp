// The assembled model: forces against energy, Jacobians against forces, constraints, momentum.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "core/model/cloth_system.hpp"
#include "core/parallel/parallel_for.hpp"
#include "core/dummy/dummy_sources.hpp"
#include "tests/support/test_support.hpp"

namespace drape {
namespace {

using testing::forces_of;
using testing::jitter;
using testing::potential_of;

ClothSystem make_system(double damping_spring = 0.0, double damping_air = 0.0) {
  ClothParams p = testing::small_cloth(4, 5);
  p.damping_spring = damping_spring;
  p.damping_air = damping_air;
  return ClothSystem(build_cloth(p), nullptr, ForceParams{});
}

TEST(ClothSystem, ForcesAreMinusPotentialGradientForEveryFamilyAndGravity) {
  const ClothSystem s = make_system();
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const Eigen::VectorXd x = jitter(s.cloth().rest_positions, 0.005, seed);
    const Eigen::VectorXd v = Eigen::VectorXd::Zero(x.size());
    const Eigen::VectorXd grad =
        testing::fd_gradient([&](const Eigen::VectorXd& xx) { return potential_of(s, xx); }, x, 1e-7);
    const Eigen::VectorXd f = forces_of(s, x, v);
    EXPECT_LT((f + grad).norm(), 1e-6 * f.norm()) << "seed " << seed;
  }
}

TEST(ClothSystem, JacobianTimesVectorMatchesForceDifferences) {
  const ClothSystem s = make_system(0.05, 0.01);
  const Eigen::VectorXd x = jitter(s.cloth().rest_positions, 0.006, 7);
  const Eigen::VectorXd v = jitter(Eigen::VectorXd::Zero(x.size()), 0.3, 8);
  const Eigen::VectorXd dx = jitter(Eigen::VectorXd::Zero(x.size()), 1.0, 9);
  const Eigen::VectorXd dv = jitter(Eigen::VectorXd::Zero(x.size()), 1.0, 10);
  const double h = 1e-7;
  const Eigen::VectorXd fd =
      (forces_of(s, x + h * dx, v + h * dv) - forces_of(s, x - h * dx, v - h * dv)) / (2 * h);
  Eigen::VectorXd jv(x.size());
  s.force_jacobian_times(ConstVecMap(x.data(), x.size()), ConstVecMap(v.data(), v.size()),
                         ConstVecMap(dx.data(), dx.size()), ConstVecMap(dv.data(), dv.size()),
                         VecMap(jv.data(), jv.size()), false);
  EXPECT_LT((jv - fd).norm(), 1e-6 * fd.norm());
}

TEST(ClothSystem, SparseJacobiansEqualTheProducts) {
  ClothSystem s = make_system(0.05, 0.01);
  s.constraints().fix_at(0, s.cloth().rest_positions.head<3>());
  const Eigen::VectorXd x = jitter(s.cloth().rest_positions, 0.006, 11);
  const Eigen::VectorXd v = jitter(Eigen::VectorXd::Zero(x.size()), 0.3, 12);
  const Eigen::VectorXd dx = jitter(Eigen::VectorXd::Zero(x.size()), 1.0, 13);
  const Eigen::VectorXd dv = jitter(Eigen::VectorXd::Zero(x.size()), 1.0, 14);
  for (const bool definite : {false, true}) {
    Eigen::SparseMatrix<double> kx, dvm;
    const ConstVecMap xm(x.data(), x.size()), vm(v.data(), v.size());
    s.force_jacobians(xm, vm, definite, kx, dvm);
    Eigen::VectorXd jv(x.size());
    s.force_jacobian_times(xm, vm, ConstVecMap(dx.data(), dx.size()),
                           ConstVecMap(dv.data(), dv.size()), VecMap(jv.data(), jv.size()),
                           definite);
    EXPECT_LT((kx * dx + dvm * dv - jv).norm(), 1e-12 * jv.norm());
    EXPECT_TRUE(jv.head<3>().isZero()) << "fixed rows are zero";
  }
}

// A 50 x 50 cloth (2500 particles, above threaded_particles_from): the blocks of every spring
// and particle are the same bits on 1, 2 and 3 threads, and applied in the pair pattern they
// are the Jacobian products.
TEST(ClothSystem, JacobianBlocksAreTheProductsOnAnyNumberOfThreads) {
  const int before = thread_count();
  ClothParams p = testing::small_cloth(50, 50);
  p.damping_spring = 0.05;
  p.damping_air = 0.01;
  const ClothSystem s(build_cloth(p), nullptr, ForceParams{});
  const Eigen::VectorXd x = jitter(s.cloth().rest_positions, 0.006, 15);
  const Eigen::VectorXd v = jitter(Eigen::VectorXd::Zero(x.size()), 0.3, 16);
  const Eigen::VectorXd dx = jitter(Eigen::VectorXd::Zero(x.size()), 1.0, 17);
  const Eigen::VectorXd dv = jitter(Eigen::VectorXd::Zero(x.size()), 1.0, 18);
  const ConstVecMap xm(x.data(), x.size()), vm(v.data(), v.size());
  for (const bool definite : {false, true}) {
    JacobianBlocks one;
    set_thread_count(1);
    s.force_jacobian_blocks(xm, vm, definite, ForceSplit::all, one);
    for (const int threads : {2, 3}) {
      set_thread_count(threads);
      JacobianBlocks blocks;
      s.force_jacobian_blocks(xm, vm, definite, ForceSplit::all, blocks);
      EXPECT_EQ(blocks.spring_x, one.spring_x) << threads << " threads";
      EXPECT_EQ(blocks.spring_v, one.spring_v) << threads << " threads";
      EXPECT_EQ(blocks.particle_x, one.particle_x) << threads << " threads";
      EXPECT_EQ(blocks.particle_v, one.particle_v) << threads << " threads";
    }
    Eigen::VectorXd product(x.size());
    for (int i = 0; i < s.num_particles(); ++i)
      particle(product, i) = one.particle_x[static_cast<std::size_t>(i)] * particle(dx, i) +
                             one.particle_v[static_cast<std::size_t>(i)] * particle(dv, i);
    const SpringList& springs = s.cloth().springs;
    for (Eigen::Index e = 0; e < springs.size(); ++e) {
      const int i = springs.first[e], j = springs.second[e];
      const auto k = static_cast<std::size_t>(e);
      const Vec3 df = one.spring_x[k] * (particle(dx, j) - particle(dx, i)) +
                      one.spring_v[k] * (particle(dv, j) - particle(dv, i));
      particle(product, i) += df;
      particle(product, j) -= df;
    }
    Eigen::VectorXd jv(x.size());
    s.force_jacobian_times(xm, vm, ConstVecMap(dx.data(), dx.size()),
                           ConstVecMap(dv.data(), dv.size()), VecMap(jv.data(), jv.size()),
                           definite);
    EXPECT_LT((product - jv).norm(), 1e-12 * jv.norm());
  }
  set_thread_count(before);
}

TEST(ClothSystem, InternalForcesConserveMomentum) {
  ClothParams p = testing::small_cloth(4, 5);
  p.damping_spring = 0.2;
  const ClothSystem s(build_cloth(p), nullptr, ForceParams{Vec3::Zero(), {}});
  const Eigen::VectorXd x = jitter(s.cloth().rest_positions, 0.006, 3);
  const Eigen::VectorXd v = jitter(Eigen::VectorXd::Zero(x.size()), 0.5, 4);
  const Eigen::VectorXd f = forces_of(s, x, v);
  Vec3 total = Vec3::Zero();
  for (int i = 0; i < s.num_particles(); ++i) total += f.segment<3>(3 * i);
  EXPECT_LT(total.norm(), 1e-13);
}

TEST(ClothSystem, GravityAndAirDampingClosedForm) {
  ClothParams p = testing::small_cloth(1, 2);
  p.damping_air = 0.3;
  const ClothSystem s(build_cloth(p), nullptr, ForceParams{});
  const Eigen::VectorXd x = s.cloth().rest_positions;  // springs at rest
  Eigen::VectorXd v = Eigen::VectorXd::Zero(6);
  v[0] = 2.0;
  const Eigen::VectorXd f = forces_of(s, x, v);
  EXPECT_NEAR(f[0], -0.6, 1e-15);
  EXPECT_NEAR(f[1], -9.81 * 0.001, 1e-15);
  EXPECT_NEAR(f[4], -9.81 * 0.001, 1e-15);
}

class Circle final : public Trajectory {
 public:
  Vec3 position(double t) const override { return Vec3(std::cos(t), std::sin(t), 0.0); }
  Vec3 velocity(double t) const override { return Vec3(-std::sin(t), std::cos(t), 0.0); }
  Vec3 acceleration(double t) const override { return -position(t); }
};

TEST(ClothSystem, FixedParticlesFollowTheirPrescribedMotionInRhsAndProjection) {
  ClothSystem s = make_system(0.1, 0.1);
  s.constraints().fix(3, std::make_shared<Circle>());
  const double t = 0.7;
  Eigen::VectorXd y = s.initial_state(t);
  const Eigen::Index n3 = 3 * s.num_particles();
  EXPECT_TRUE(y.segment<3>(9).isApprox(Vec3(std::cos(t), std::sin(t), 0.0)));
  EXPECT_TRUE(y.segment<3>(n3 + 9).isApprox(Vec3(-std::sin(t), std::cos(t), 0.0)));
  Eigen::VectorXd y_dot(y.size());
  s.rhs(t, ConstVecMap(y.data(), y.size()), VecMap(y_dot.data(), y_dot.size()));
  EXPECT_TRUE(y_dot.segment<3>(9).isApprox(Vec3(-std::sin(t), std::cos(t), 0.0)));
  EXPECT_TRUE(y_dot.segment<3>(n3 + 9).isApprox(-Vec3(std::cos(t), std::sin(t), 0.0)));
  // A free particle's acceleration is F/m.
  const Eigen::VectorXd f = forces_of(s, y.head(n3), y.tail(n3));
  EXPECT_TRUE(y_dot.segment<3>(n3).isApprox(f.head<3>() / 0.001));
  s.constraints().release(3);
  EXPECT_FALSE(s.constraints().is_fixed(3));
  EXPECT_TRUE(s.constraints().fixed_particles().empty());
}

// The IMEX splits: each split's two sides add up to every force, for forces, Jacobians and
// right-hand sides, on a cloth in contact with an object with a fixed particle. The springs-only
// split leaves the collision force explicit (with gravity and air damping); springs+collision
// moves it to the implicit side (docs/model.md section 5).
TEST(ClothSystem, ImplicitAndExplicitPartsAddUpToAll) {
  const auto owner = testing::cloth_against_sphere(CollisionModel::particle);
  const ClothSystem& s = *owner;
  const Eigen::Index n3 = 3 * s.num_particles();
  const Eigen::VectorXd x = jitter(s.cloth().rest_positions, 0.003, 11);
  const Eigen::VectorXd v = jitter(Eigen::VectorXd::Zero(n3), 0.3, 12);
  ASSERT_GT(s.energy(x, v).collision, 0.0);
  const Eigen::VectorXd dx = jitter(Eigen::VectorXd::Zero(n3), 1.0, 13);
  const Eigen::VectorXd dv = jitter(Eigen::VectorXd::Zero(n3), 1.0, 14);
  Eigen::VectorXd collision_force(n3);
  for (int i = 0; i < s.num_particles(); ++i)
    particle(collision_force, i) = s.collision().force(i, particle(x, i));

  struct Split { ForceSplit implicit_part, explicit_part; const char* name; };
  for (const Split split : {Split{ForceSplit::springs, ForceSplit::non_springs, "springs"},
                            Split{ForceSplit::springs_and_collision, ForceSplit::body,
                                  "springs+collision"}}) {
    SCOPED_TRACE(split.name);
    auto parts = [&](auto evaluate) {
      Eigen::VectorXd all(n3), implicit_part(n3), explicit_part(n3);
      evaluate(ForceSplit::all, all);
      evaluate(split.implicit_part, implicit_part);
      evaluate(split.explicit_part, explicit_part);
      EXPECT_LT((implicit_part + explicit_part - all).norm(), 1e-12 * all.norm());
      EXPECT_GT(implicit_part.norm(), 0.0);
      EXPECT_GT(explicit_part.norm(), 0.0);
    };
    parts([&](ForceSplit part, Eigen::VectorXd& f) { s.forces(x, v, f, part); });
    for (const bool definite : {false, true})
      parts([&](ForceSplit part, Eigen::VectorXd& out) {
        s.force_jacobian_times(x, v, dx, dv, out, definite, part);
      });

    Eigen::VectorXd y(2 * n3);
    y << x, v;
    Eigen::VectorXd all(2 * n3), implicit_part(2 * n3), explicit_part(2 * n3);
    s.rhs(0.0, y, all, ForceSplit::all);
    s.rhs(0.0, y, implicit_part, split.implicit_part);
    s.rhs(0.0, y, explicit_part, split.explicit_part);
    EXPECT_LT((implicit_part + explicit_part - all).norm(), 1e-12 * all.norm());
    EXPECT_TRUE(explicit_part.head(n3).isZero()) << "x' = v is on the implicit side";
  }
  // Where the collision force goes: the difference of the two implicit sides.
  Eigen::VectorXd springs(n3), springs_and_collision(n3);
  s.forces(x, v, springs, ForceSplit::springs);
  s.forces(x, v, springs_and_collision, ForceSplit::springs_and_collision);
  EXPECT_GT(collision_force.norm(), 0.0);
  EXPECT_LT((springs_and_collision - springs - collision_force).norm(), 1e-12 * collision_force.norm());
}

// docs/model.md section 4.12: while frozen, the lagged friction is part of the collision term:
// the forces gain -grad D (D = energy().friction, by central differences), the definite
// Jacobian -Hess D (against force differences), and released, everything is as before. The
// velocity-level pass cuts each contact's tangential velocity by mu dt |F_c| / m.
TEST(ClothSystem, FrozenFrictionIsInTheForcesEnergyAndJacobianAndReleasedIsGone) {
  ClothParams p = testing::small_cloth(3, 3);
  ForceParams params;
  params.collision = CollisionParams{0.01, 1000.0, CollisionModel::smooth, 0.4, 1e-3};
  const auto sphere = std::make_shared<const Dummy>(make_dummy(
      nlohmann::json{{"builtin", "sphere"}, {"radius", 0.05}, {"center", {0.02, 0.97, 0.055}}},
      "test", "dummy", "."));
  ClothSystem s(build_cloth(p), sphere, params);
  const Eigen::Index n3 = 3 * s.num_particles();
  const Eigen::VectorXd x0 = s.cloth().rest_positions;  // within delta of the sphere
  const Eigen::VectorXd v = Eigen::VectorXd::Zero(n3);
  const Eigen::VectorXd before = forces_of(s, x0, v);
  const double h = 0.01;
  s.freeze_friction(x0, h);
  // Moved within and beyond the sticking zone (eps = 1e-5 m).
  const Eigen::VectorXd x = jitter(x0, 2e-5, 3);
  const Eigen::VectorXd f = forces_of(s, x, v);
  s.release_friction();
  const Eigen::VectorXd friction_force = f - forces_of(s, x, v);
  ASSERT_GT(friction_force.norm(), 0.0);
  s.freeze_friction(x0, h);
  const auto dissipation = [&](const Eigen::VectorXd& at) {
    return s.energy(at, v).friction;
  };
  const Eigen::VectorXd gradient = testing::fd_gradient(dissipation, x, 1e-9);
  EXPECT_LT((friction_force + gradient).norm(), 1e-6 * friction_force.norm());
  const Eigen::VectorXd dx = jitter(Eigen::VectorXd::Zero(n3), 1.0, 4);
  Eigen::VectorXd product(n3);
  s.force_jacobian_times(x, v, dx, Eigen::VectorXd::Zero(n3), product, false);
  const double d = 1e-10;
  const Eigen::VectorXd difference = (forces_of(s, x + d * dx, v) - forces_of(s, x - d * dx, v)) / (2 * d);
  EXPECT_LT((product - difference).norm(), 1e-5 * difference.norm());
  s.release_friction();
  EXPECT_EQ(forces_of(s, x0, v), before);
  EXPECT_EQ(s.energy(x, v).friction, 0.0);

  // Velocity level: a particle in contact, moving tangentially at 0.5 m/s, over dt = 1 ms.
  int i = 0;
  Vec3 contact = Vec3::Zero();
  for (; i < s.num_particles() && contact.isZero(); ++i) contact = s.collision().force(i, particle(x0, i));
  --i;
  ASSERT_GT(contact.norm(), 0.0);
  const Vec3 normal = contact.normalized();
  const Vec3 tangent = normal.cross(Vec3::UnitX()).normalized();
  Eigen::VectorXd w = Eigen::VectorXd::Zero(n3);
  particle(w, i) = 0.5 * tangent - 0.1 * normal;
  s.apply_velocity_friction(x0, w, 1e-3);
  const double cut = 0.4 * 1e-3 * contact.norm() / p.particle_mass;
  EXPECT_NEAR(particle(w, i).dot(tangent), 0.5 - cut, 1e-12);
  EXPECT_NEAR(particle(w, i).dot(normal), -0.1, 1e-12);
}

// docs/friction.md, "Smooth Coulomb force": a split that asks for it gains, per particle in
// contact, smooth_coulomb_force at the particle's own velocity; its velocity Jacobian is in
// dF/dv (against force differences in v, with the air damping's beside it); with mu = 0 the
// forces are the frictionless ones bit for bit.
TEST(ClothSystem, SmoothFrictionIsInTheSplitsThatAskAndItsJacobianInDfDv) {
  ClothParams p = testing::small_cloth(3, 3);
  p.damping_air = 0.01;
  const auto sphere = std::make_shared<const Dummy>(make_dummy(
      nlohmann::json{{"builtin", "sphere"}, {"radius", 0.05}, {"center", {0.02, 0.97, 0.055}}},
      "test", "dummy", "."));
  ForceSplit with_friction = ForceSplit::all;
  with_friction.with_smooth_friction = true;
  for (const double mu : {0.0, 0.4}) {
    ForceParams params;
    params.collision = CollisionParams{0.01, 1000.0, CollisionModel::smooth, mu, 1e-3};
    ClothSystem s(build_cloth(p), sphere, params);
    const Eigen::Index n3 = 3 * s.num_particles();
    const Eigen::VectorXd x = s.cloth().rest_positions;  // within delta of the sphere
    // Speeds around epsilon_v: within the mollifier and beyond it.
    const Eigen::VectorXd v = jitter(Eigen::VectorXd::Zero(n3), 2e-3, 5);
    Eigen::VectorXd plain(n3), with(n3);
    s.forces(x, v, plain, ForceSplit::all);
    s.forces(x, v, with, with_friction);
    if (mu == 0.0) {
      EXPECT_EQ(with, plain);
      continue;
    }
    int touching = 0;
    for (int i = 0; i < s.num_particles(); ++i) {
      const Vec3 contact = s.collision().force(i, particle(x, i));
      touching += contact.norm() > 0.0;
      const Vec3 expected = smooth_coulomb_force(contact, particle(v, i), mu, 1e-3);
      EXPECT_LT((particle(with, i) - particle(plain, i) - expected).norm(),
                1e-12 * (1.0 + particle(plain, i).norm()));
    }
    ASSERT_GT(touching, 0);
    const Eigen::VectorXd dv = jitter(Eigen::VectorXd::Zero(n3), 1.0, 6);
    Eigen::VectorXd product(n3), difference(n3), ahead(n3), behind(n3);
    s.force_jacobian_times(x, v, Eigen::VectorXd::Zero(n3), dv, product, false, with_friction);
    const double d = 1e-9;
    s.forces(x, v + d * dv, ahead, with_friction);
    s.forces(x, v - d * dv, behind, with_friction);
    difference = (ahead - behind) / (2 * d);
    EXPECT_LT((product - difference).norm(), 1e-5 * difference.norm());
    Eigen::SparseMatrix<double> dfdx, dfdv;
    s.force_jacobians(x, v, true, dfdx, dfdv, with_friction);
    EXPECT_LT((dfdv * dv - product).norm(), 1e-12 * product.norm());
  }
}

}  // namespace
}  // namespace drape
