// The collision term of each model: its force, energy, Jacobian and penetration correction
// against their closed forms and the queries they use.
#include <gtest/gtest.h>
#include <random>

#include "core/collision/collision.hpp"
#include "core/dummy/dummy_sources.hpp"

namespace drape {
namespace {

TEST(ParticleCollision, ForceUsesTheQueryDistanceWithTheSameBits) {
  const auto dummy = std::make_shared<const Dummy>(
      make_dummy(nlohmann::json{{"builtin", "dress-form"}}, "test", "dummy", "."));
  const CollisionParams params{0.01, 1000.0, CollisionModel::particle};
  const Collision collision(dummy, params, 1);
  std::mt19937 rng(19);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int hits = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const double y = 1.05 + 0.2 * u(rng), theta = 1.5 * u(rng);
    const Eigen::Vector2d axis = dummy->axis_at(y);
    const double r = dummy->surface_radius(y, theta) + 0.01 * u(rng);
    const Vec3 x(axis.x() + r * std::sin(theta), y, axis.y() + r * std::cos(theta));
    const NearestObjectParticle hit = dummy->nearest_within(x, params.threshold);
    if (hit.index < 0) continue;
    // The query's distance is the norm that collision_force would take itself.
    ASSERT_EQ(collision.force(0, x), collision_force(x - dummy->position(hit.index),
                                                     dummy->normal(hit.index), params.stiffness,
                                                     params.threshold));
    ++hits;
  }
  EXPECT_GT(hits, 1000);
}

// Cloth particles scattered within 1 cm of the dress form's front.
std::vector<Vec3> near_the_front(const Dummy& dummy, int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Vec3> x(static_cast<std::size_t>(count));
  for (Vec3& p : x) {
    const double y = 1.05 + 0.2 * u(rng), theta = 1.5 * u(rng);
    const Eigen::Vector2d axis = dummy.axis_at(y);
    const double r = dummy.surface_radius(y, theta) + 0.01 * u(rng);
    p = Vec3(axis.x() + r * std::sin(theta), y, axis.y() + r * std::cos(theta));
  }
  return x;
}

Eigen::VectorXd flattened(const std::vector<Vec3>& x) {
  Eigen::VectorXd out(3 * static_cast<Eigen::Index>(x.size()));
  for (std::size_t i = 0; i < x.size(); ++i) out.segment<3>(3 * static_cast<Eigen::Index>(i)) = x[i];
  return out;
}

std::shared_ptr<const Dummy> dress_form() {
  return std::make_shared<const Dummy>(
      make_dummy(nlohmann::json{{"builtin", "dress-form"}}, "test", "dummy", "."));
}

// 500 cloth particles near the dress form's front, their collision and their unpaired forces.
struct NearTheFront {
  NearTheFront(CollisionModel model, unsigned seed)
      : dummy(dress_form()),
        params{0.01, 1000.0, model},
        x(near_the_front(*dummy, n, seed)),
        collision(dummy, params, n) {
    for (int i = 0; i < n; ++i) forces.push_back(collision.force(i, at(i)));
  }
  const Vec3& at(int i) const { return x[static_cast<std::size_t>(i)]; }
  /// Particle i moved by up to 5 mm, a few times a Newton iterate's move in the drape at 2e-4 s.
  Vec3 moved(int i) { return at(i) + 0.005 * Vec3(u(rng), u(rng), u(rng)); }

  static constexpr int n = 500;
  std::shared_ptr<const Dummy> dummy;
  CollisionParams params;
  std::vector<Vec3> x;
  Collision collision;
  std::vector<Vec3> forces;
  std::mt19937 rng{1};
  std::uniform_real_distribution<double> u{-1.0, 1.0};
};

TEST(ContactPairing, PairsTheNearestParticleAndChangesNothingWhereItPaired) {
  NearTheFront f(CollisionModel::particle, 5);
  f.collision.pair_contacts(flattened(f.x));
  int in_contact = 0;
  for (int i = 0; i < f.n; ++i) {
    ASSERT_EQ(f.collision.paired(i), f.dummy->nearest_within(f.at(i), 2.0 * f.params.threshold).index);
    ASSERT_EQ(f.collision.force(i, f.at(i)), f.forces[static_cast<std::size_t>(i)]) << "particle " << i;
    in_contact += !f.forces[static_cast<std::size_t>(i)].isZero();
  }
  EXPECT_GT(in_contact, 100);
}

// Paired, the point repulsion is linearised at the pairing position: a spring along the fixed
// direction n from the paired object particle, continuous where the nearest object particle
// switches.
TEST(ContactPairing, KeepsTheLinearisedPairWhenTheNearestParticleSwitches) {
  NearTheFront f(CollisionModel::particle, 7);
  const Dummy& dummy = *f.dummy;
  const double k = f.params.stiffness, delta = f.params.threshold;
  f.collision.pair_contacts(flattened(f.x));
  int switched = 0;
  for (int i = 0; i < f.n; ++i) {
    const int o = f.collision.paired(i);
    if (o < 0) continue;
    const Vec3 moved = f.moved(i);
    const Vec3 d0 = f.at(i) - dummy.position(o);
    const double gap = d0.norm() + (d0 / d0.norm()).dot(moved - f.at(i));
    const Vec3 expected = gap < delta ? Vec3(k * (delta - gap) * d0 / d0.norm()) : Vec3::Zero();
    ASSERT_LT((f.collision.force(i, moved) - expected).norm(), 1e-12 * k * delta);
    const int nearest = dummy.nearest_within(moved, delta).index;
    if (nearest >= 0 && nearest != o) ++switched;
  }
  EXPECT_GT(switched, 20) << "the moves cross switches of the nearest object particle";
  f.collision.unpair_contacts();
  for (int i = 0; i < f.n; ++i) {
    ASSERT_EQ(f.collision.paired(i), -1);
    ASSERT_EQ(f.collision.force(i, f.at(i)), f.forces[static_cast<std::size_t>(i)]);
  }
}

// A corrected penetration puts a cloth particle exactly on an object particle, where the point
// repulsion's direction is undefined (the docs/model.md force takes the object particle's normal): paired,
// the force there is the same, and nearby it keeps that direction instead of turning around.
TEST(ContactPairing, ParticleOnItsObjectParticlePushesAlongTheNormal) {
  const auto dummy = dress_form();
  const CollisionParams params{0.01, 1000.0, CollisionModel::particle};
  const int o = dummy->size() / 2;
  const Vec3 on = dummy->position(o), normal = dummy->normal(o);
  Collision collision(dummy, params, 1);
  const Vec3 unpaired = collision.force(0, on);
  collision.pair_contacts(on);
  EXPECT_EQ(collision.force(0, on), unpaired);
  EXPECT_EQ(unpaired, params.stiffness * params.threshold * normal);
  const Vec3 step = 1e-4 * Vec3(1.0, -2.0, 0.5);
  for (const Vec3& x : {Vec3(on + step), Vec3(on - step)}) {
    const double gap = normal.dot(x - on);
    EXPECT_LT((collision.force(0, x) - params.stiffness * (params.threshold - gap) * normal).norm(),
              1e-12);
  }
}

// The surface model's paired gap is the tangent plane at the pairing position: the same force
// there, and across the interpolated surface's section heights and angle bins, where the
// surface's gradient jumps, a force that follows the plane continuously.
TEST(ContactPairing, SurfaceModelKeepsTheTangentPlaneOfThePairingPosition) {
  NearTheFront f(CollisionModel::surface, 9);
  const double k = f.params.stiffness, delta = f.params.threshold;
  f.collision.pair_contacts(flattened(f.x));
  int jumps = 0;
  for (int i = 0; i < f.n; ++i) {
    const Vec3& p = f.at(i);
    ASSERT_EQ(f.collision.paired(i), -1) << "no object particles in the surface model";
    ASSERT_EQ(f.collision.force(i, p), f.forces[static_cast<std::size_t>(i)]) << "particle " << i;
    const auto g = f.dummy->surface_gap(p);
    if (!g || g->gap >= delta) continue;
    const Vec3 moved = f.moved(i);
    const double plane_gap = g->gap + g->gradient.dot(moved - p);
    const Vec3 expected =
        plane_gap < delta ? Vec3(k * (delta - plane_gap) * g->gradient) : Vec3::Zero();
    ASSERT_EQ(f.collision.force(i, moved), expected);
    const auto g_moved = f.dummy->surface_gap(moved);
    if (g_moved && (g_moved->gradient - g->gradient).norm() > 0.01) ++jumps;
  }
  EXPECT_GT(jumps, 20) << "the moves cross edges of the interpolated surface";
}

// The paired force is minus the paired energy's gradient, the paired Jacobian the force's
// derivative (central differences), for both models, away from the threshold's kink.
TEST(ContactPairing, ForceAndJacobianAreTheEnergyDerivatives) {
  for (const CollisionModel model : {CollisionModel::particle, CollisionModel::surface}) {
    NearTheFront f(model, 12);
    f.collision.pair_contacts(flattened(f.x));
    const double h = 1e-7, delta = f.params.threshold;
    int checked = 0;
    for (int i = 0; i < f.n; ++i) {
      const Vec3 x = f.moved(i);
      const Vec3 force = f.collision.force(i, x);
      if (force.isZero() || f.collision.energy(i, x) < 1e-6 * delta * delta) continue;
      const Mat3 jacobian = f.collision.jacobian(i, x, false);
      for (int a = 0; a < 3; ++a) {
        const Vec3 e = h * Vec3::Unit(a);
        const double de = f.collision.energy(i, x + e) - f.collision.energy(i, x - e);
        ASSERT_NEAR(-de / (2 * h), force[a], 1e-6 * force.norm()) << "particle " << i;
        const Vec3 df = f.collision.force(i, x + e) - f.collision.force(i, x - e);
        ASSERT_LT((df / (2 * h) - jacobian.col(a)).norm(), 1e-6 * jacobian.norm() + 1e-9);
      }
      ++checked;
    }
    EXPECT_GT(checked, 50);
  }
}

TEST(DummyParticlesWithin, MatchesTheBruteForceScan) {
  const Dummy dummy(cylinder_sections(0.1, 0.0, 0.0, 1.0, 0.5, 21, 24));
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.15, 0.15);
  std::vector<int> found;
  for (int trial = 0; trial < 500; ++trial) {
    const Vec3 p(u(rng), 0.75 + 2 * u(rng), u(rng));
    dummy.particles_within(p, 0.03, found);
    std::vector<int> expected;
    for (int o = 0; o < dummy.size(); ++o)
      if ((dummy.position(o) - p).squaredNorm() < 0.03 * 0.03) expected.push_back(o);
    ASSERT_EQ(found, expected);
  }
}

// A sheared stack: the axis moves with height and the radius varies with height and angle, so
// every term of the gap's gradient is exercised.
Dummy leaning_stack() {
  DummySections s;
  const int sections = 9, points = 12;
  s.radius.resize(sections, points);
  for (int k = 0; k < sections; ++k) {
    s.y.push_back(1.2 - 0.05 * k);
    s.cx.push_back(0.01 * k);
    s.cz.push_back(-0.005 * k * k);
    for (int j = 0; j < points; ++j) s.radius(k, j) = 0.1 + 0.004 * k + 0.01 * std::sin(j);
  }
  return Dummy(s);
}

// Penetration decisions with the cached outside margins equal Dummy::inside along random walks
// that cross the surface and the end sections, with steps below and far above the margins.
void expect_penetration_tests_equal_inside(const std::shared_ptr<const Dummy>& dummy) {
  const int walkers = 200;
  const Collision collision(dummy, {0.01, 100.0, CollisionModel::particle}, walkers);
  const auto& ys = dummy->sections().y;
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Vec3> x(walkers);
  for (int w = 0; w < walkers; ++w) {
    const double y = 0.5 * (ys.front() + ys.back()) + 0.55 * (ys.front() - ys.back()) * u(rng);
    const double theta = 3.2 * u(rng);
    const Eigen::Vector2d axis = dummy->axis_at(y);
    const double r = dummy->surface_radius(y, theta) + 0.01 * u(rng);
    x[w] = Vec3(axis.x() + r * std::sin(theta), y, axis.y() + r * std::cos(theta));
  }
  int inside = 0, outside = 0;
  for (int step = 0; step < 400; ++step) {
    const double size = step % 50 == 49 ? 0.02 : 2e-4 * (1 + step % 7);
    for (int w = 0; w < walkers; ++w) {
      x[w] += size * Vec3(u(rng), u(rng), u(rng));
      Vec3 corrected = x[w], v = Vec3::Zero();
      const bool expected = dummy->inside(x[w]);
      ASSERT_EQ(collision.correct_penetration(w, corrected, v), expected)
          << "step " << step << " walker " << w;
      ++(expected ? inside : outside);
    }
  }
  EXPECT_GT(inside, 5000);
  EXPECT_GT(outside, 5000);
}

TEST(PenetrationCorrection, EqualsInsideAlongRandomWalksOnTheDressForm) {
  expect_penetration_tests_equal_inside(std::make_shared<const Dummy>(
      make_dummy(nlohmann::json{{"builtin", "dress-form"}}, "test", "dummy", ".")));
}

TEST(PenetrationCorrection, EqualsInsideAlongRandomWalksOnALeaningStack) {
  expect_penetration_tests_equal_inside(std::make_shared<const Dummy>(leaning_stack()));
}

TEST(DummyOutsideMargin, NoPointWithinTheMarginIsInside) {
  for (const Dummy& dummy : {leaning_stack(), make_dummy(nlohmann::json{{"builtin", "dress-form"}},
                                                         "test", "dummy", ".")}) {
    const auto& ys = dummy.sections().y;
    std::mt19937 rng(17);
    std::uniform_real_distribution<double> u(-1.0, 1.0), unit(0.0, 1.0);
    int useful = 0;
    for (int trial = 0; trial < 2000; ++trial) {
      const double y = 0.5 * (ys.front() + ys.back()) + 0.6 * (ys.front() - ys.back()) * u(rng);
      const double theta = 3.2 * u(rng);
      const Eigen::Vector2d axis = dummy.axis_at(y);
      const double r = dummy.surface_radius(y, theta) + 0.03 * u(rng);
      const Vec3 p(axis.x() + r * std::sin(theta), y, axis.y() + r * std::cos(theta));
      const double margin = dummy.outside_margin(p);
      if (margin == 0.0) continue;
      ASSERT_FALSE(dummy.inside(p));
      ++useful;
      // Points towards the surface and anywhere, out to just below the margin.
      for (int k = 0; k < 20; ++k) {
        const Vec3 direction = k % 2 ? Vec3(u(rng), u(rng), u(rng)).normalized()
                                     : Vec3(axis.x() - p.x(), 0.0, axis.y() - p.z()).normalized();
        const double reach = k < 10 ? margin * (1.0 - 1e-12) : margin * unit(rng);
        ASSERT_FALSE(dummy.inside(p + reach * direction)) << "trial " << trial << " k " << k;
      }
    }
    EXPECT_GT(useful, 500);
  }
}

TEST(SurfaceCollision, ForceIsMinusEnergyGradient) {
  const auto dummy = std::make_shared<const Dummy>(leaning_stack());
  const CollisionParams params{0.02, 300.0, CollisionModel::surface};
  const Collision collision(dummy, params, 1);
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int checked = 0;
  for (int trial = 0; trial < 400; ++trial) {
    // Mid-way between sections and between particles: away from the kinks of the piecewise
    // linear surface, where the energy is smooth and central differences are exact to O(h^2).
    const int k = static_cast<int>(u(rng) * 8), j = static_cast<int>(u(rng) * 12);
    const double y = 1.2 - 0.05 * (k + 0.3 + 0.4 * u(rng));
    const double theta = 2 * M_PI / 12 * (j + 0.3 + 0.4 * u(rng));
    const Eigen::Vector2d axis = dummy->axis_at(y);
    const double r = dummy->surface_radius(y, theta) + 0.03 * u(rng) - 0.005;
    const Vec3 x(axis.x() + r * std::sin(theta), y, axis.y() + r * std::cos(theta));
    const Vec3 f = collision.force(0, x);
    if (f.isZero()) continue;
    Vec3 grad;
    for (int a = 0; a < 3; ++a) {
      Vec3 h = Vec3::Zero();
      h[a] = 1e-7;
      grad[a] = (collision.energy(0, x + h) - collision.energy(0, x - h)) / 2e-7;
    }
    EXPECT_LT((f + grad).norm(), 1e-5 * f.norm()) << "trial " << trial;
    ++checked;
  }
  EXPECT_GT(checked, 100);
}

TEST(SurfaceCollision, ClosedFormOnACylinder) {
  const auto dummy = std::make_shared<const Dummy>(cylinder_sections(0.1, 0.0, 0.0, 1.0, 0.5, 11, 16));
  const Collision collision(dummy, {0.02, 500.0, CollisionModel::surface}, 1);
  // 5 mm outside the surface at 30 degrees: pushed radially with k (delta - g) = 500 * 0.015.
  const double theta = M_PI / 6, r = 0.105;
  const Vec3 x(r * std::sin(theta), 0.75, r * std::cos(theta));
  const Vec3 f = collision.force(0, x);
  // The polygon between particles is not the circle: R at 30 degrees is the linear mix of the
  // radii at 22.5 and 45 degrees, both 0.1, so the gap is exactly 5 mm.
  EXPECT_LT((f - 7.5 * Vec3(std::sin(theta), 0, std::cos(theta))).norm(), 1e-9);
  EXPECT_NEAR(collision.energy(0, x), 0.5 * 500 * 0.015 * 0.015, 1e-12);
  EXPECT_TRUE(collision.force(0, Vec3(0.0, 0.75, 0.121)).isZero()) << "beyond the threshold";
  EXPECT_TRUE(collision.force(0, Vec3(0.0, 1.01, 0.1)).isZero()) << "above the open top";
}

TEST(PenetrationCorrection, ParticleInsideEndsOutsideForBothModels) {
  const auto dummy = std::make_shared<const Dummy>(leaning_stack());
  for (const CollisionModel model : {CollisionModel::particle, CollisionModel::surface}) {
    const Collision collision(dummy, {0.01, 100.0, model}, 1);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int trial = 0; trial < 200; ++trial) {
      const double y = 1.19 - 0.38 * u(rng), theta = 2 * M_PI * u(rng);
      const Eigen::Vector2d axis = dummy->axis_at(y);
      const double r = dummy->surface_radius(y, theta) * (0.2 + 0.75 * u(rng));
      Vec3 x(axis.x() + r * std::sin(theta), y, axis.y() + r * std::cos(theta));
      Vec3 v(-std::sin(theta), -0.5, -std::cos(theta));  // moving inwards and down
      ASSERT_TRUE(dummy->inside(x));
      ASSERT_TRUE(collision.correct_penetration(0, x, v));
      // On the surface (an object particle, or the surface point itself) or outside it: a
      // round-off below zero is the surface.
      EXPECT_GE(dummy->surface_gap(x)->gap, -1e-12) << "trial " << trial;
      const Vec3 normal = model == CollisionModel::surface
                              ? dummy->surface_gap(x)->gradient.normalized()
                              : dummy->normal(dummy->nearest(x).index);
      EXPECT_GE(v.dot(normal), -1e-12) << "no inward normal velocity left";
    }
  }
}

}  // namespace
}  // namespace drape
