// The hold's particle located inside a step (docs/model.md section 7, "Hold"): the particle
// the hand reaches first, whatever the step; searched alone and through the manipulator.
#include <gtest/gtest.h>

#include <cmath>

#include "core/manipulations/hold_search.hpp"
#include "core/manipulations/manipulations.hpp"
#include "tests/support/test_support.hpp"

namespace drape {
namespace {

// A horizontal 6 x 6 cloth at y = 1 with 2 cm spacing, columns along x and rows along z,
// pinned at two corners, and a hand 1 cm above it crossing row 2 along +x at 1.5 m/s from
// x = -8 cm. The hand comes within the 1.5 cm threshold of (2, 0) first, at x = -1.12 cm,
// t = 0.0459 s; at the 1/30 s step's end, t = 0.0667 s, it is 2 cm on, right above (2, 1).
// With `cloth_moves`, the hand stays at its start and the cloth slides along -x at 1.5 m/s: the
// same motion relative to the cloth, found only if the cloth is followed inside the step too.
struct CrossingHand {
  static Vec3 hand_at(double t) { return Vec3(-0.08 + 1.5 * t, 1.01, 0.04); }
  static Vec3 cloth_shift(double t) { return Vec3(-1.5 * t, 0, 0); }

  std::unique_ptr<ClothSystem> system;
  HandTrack track;

  bool cloth_moves;

  explicit CrossingHand(bool moving_cloth = false) : cloth_moves(moving_cloth) {
    ClothParams p = testing::small_cloth(6, 6);
    p.origin = Vec3(0, 1, 0);
    p.row_dir = Vec3(0, 0, 1);
    system = std::make_unique<ClothSystem>(build_cloth(p), nullptr, ForceParams{});
    system->constraints().fix_at(0, system->cloth().rest_positions.segment<3>(0));
    system->constraints().fix_at(5, system->cloth().rest_positions.segment<3>(15));
    // Samples every 10 ms from before the start: the track's interior is then the straight
    // line (its end segments ease in and out).
    std::vector<HandFrame> frames(61);
    for (int k = 0; k < 61; ++k) {
      frames[k].t = 0.01 * (k - 10);
      frames[k].right = HandSample{cloth_moves ? hand_at(0.0) : hand_at(frames[k].t), false};
    }
    track = HandTrack(frames, SensorTransform{}, TimeMap{}, TrackPolicy{});
  }

  // The first hold when the manipulator is updated at the ends of steps of size h, the cloth
  // at rest (the hold fixes the particle: once per scene).
  ManipulationEvent first_hold(double h) {
    ManipulationParams params;
    params.hold_threshold = 0.015;
    Manipulator manipulator(*system, &track, params);
    const Eigen::VectorXd rest = system->initial_state(0.0);
    for (int k = 0; k * h < 0.2; ++k) {
      Eigen::VectorXd y = rest;
      if (cloth_moves)
        for (int i = 0; i < system->num_particles(); ++i) y.segment<3>(3 * i) += cloth_shift(k * h);
      manipulator.update(k * h, y);
      for (const ManipulationEvent& e : manipulator.events())
        if (e.type == "hold") return e;
    }
    return {};
  }
};

TEST(HoldSearch, SearchesTheWholeStepOnceItsStartIsKnown) {
  CrossingHand scene;
  const ClothSystem& system = *scene.system;
  const Eigen::VectorXd rest = system.initial_state(0.0);
  const double end = 2.0 / 30.0;
  HoldSearch fresh;  // no previous update: only the step's end is tested
  EXPECT_EQ(fresh.first_reached_particle(system, scene.track, Hand::Right, end, rest, 0.015),
            system.cloth().index(2, 1));
  HoldSearch search;
  search.finish_update(0.0, rest, system.num_particles(), true);
  EXPECT_EQ(search.first_reached_particle(system, scene.track, Hand::Right, end, rest, 0.015),
            system.cloth().index(2, 0));
  // Before the hand comes within the threshold of any particle, nothing is reached.
  EXPECT_EQ(search.first_reached_particle(system, scene.track, Hand::Right, 0.04, rest, 0.015),
            -1);
}

TEST(HoldSearch, NearestFreeParticleSkipsFixedOnes) {
  CrossingHand scene;
  ClothSystem& system = *scene.system;
  const Eigen::VectorXd rest = system.initial_state(0.0);
  const int corner = 0;  // fixed by the scene, at the origin
  const Vec3 above = rest.segment<3>(3 * corner) + Vec3(0, 0.001, 0);
  double distance = 0.0;
  const int nearest = nearest_free_particle(system, above, rest, distance);
  EXPECT_NE(nearest, corner);
  EXPECT_NEAR(distance, (rest.segment<3>(3 * nearest) - above).norm(), 1e-15);
  // The corner's neighbours are 2 cm away.
  EXPECT_NEAR(distance, std::sqrt(0.02 * 0.02 + 0.001 * 0.001), 1e-12);
}

TEST(HoldLocation, TakesTheParticleTheHandReachedFirstAtAnyStep) {
  const double entry = (0.08 - std::sqrt(0.015 * 0.015 - 0.01 * 0.01)) / 1.5;
  for (double h : {2e-4, 1e-3, 1.0 / 30.0, 0.05}) {
    CrossingHand scene;
    const int first = scene.system->cloth().index(2, 0);
    const ManipulationEvent hold = scene.first_hold(h);
    EXPECT_EQ(hold.particle, first) << h;
    // Found at the first step end at or after the entry; the snap is the distance there.
    EXPECT_GE(hold.t, entry - 1e-12) << h;
    EXPECT_LT(hold.t, entry + h) << h;
    const Vec3 hand = CrossingHand::hand_at(hold.t);
    const Vec3 x = scene.system->cloth().rest_positions.segment<3>(3 * first);
    EXPECT_NEAR(hold.value, (x - hand).norm(), 1e-9) << h;
  }
}

TEST(HoldLocation, AtTheStepEndTheHandIsNearerTheNextParticle) {
  // Why the location is needed: at the 1/30 s step's end the nearest particle is (2, 1).
  CrossingHand scene;
  const Vec3 hand = CrossingHand::hand_at(2.0 / 30.0);
  const auto& x = scene.system->cloth().rest_positions;
  const int first = scene.system->cloth().index(2, 0), next = scene.system->cloth().index(2, 1);
  EXPECT_LT((x.segment<3>(3 * next) - hand).norm(), (x.segment<3>(3 * first) - hand).norm());
  EXPECT_GT(scene.first_hold(1.0 / 30.0).value, 0.015);  // (2, 0) is past the threshold then
}

TEST(HoldLocation, FollowsTheClothInsideTheStep) {
  // The cloth moves under a still hand: at every step the particle reached first is (2, 0),
  // which a search against the cloth at the step's end would miss at 1/30 s and 50 ms.
  const double entry = (0.08 - std::sqrt(0.015 * 0.015 - 0.01 * 0.01)) / 1.5;
  for (double h : {2e-4, 1e-3, 1.0 / 30.0, 0.05}) {
    CrossingHand scene(true);
    const int first = scene.system->cloth().index(2, 0);
    const ManipulationEvent hold = scene.first_hold(h);
    EXPECT_EQ(hold.particle, first) << h;
    EXPECT_GE(hold.t, entry - 1e-12) << h;
    EXPECT_LT(hold.t, entry + h) << h;
    const Vec3 x = scene.system->cloth().rest_positions.segment<3>(3 * first) +
                   CrossingHand::cloth_shift(hold.t);
    EXPECT_NEAR(hold.value, (x - CrossingHand::hand_at(0.0)).norm(), 1e-9) << h;
  }
}

}  // namespace
}  // namespace drape
