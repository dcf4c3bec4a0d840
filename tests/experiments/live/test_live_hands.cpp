// LiveHands (experiments/live/live_hands.hpp): the live track never changes where the simulation
// may already be, so that a replay of the recorded frames is the same run (docs/live.md).
#include <algorithm>
#include "experiments/live/live_hands.hpp"

#include <cmath>
#include <limits>
#include <gtest/gtest.h>

namespace drape {
namespace {

constexpr double margin = 2e-4;
// A loop that wants to go as far as the hands allow (the wall clock ahead of it).
constexpr double ahead = std::numeric_limits<double>::infinity();

HandSample at(double x, double y, double z) { return HandSample{Vec3(x, y, z), false}; }

TEST(LiveHands, NoHandNoLimitNoFrames) {
  LiveHands hands(TrackPolicy{}, {}, margin);
  HandTrack track;
  hands.sample(0.0, ahead, track);
  EXPECT_TRUE(std::isinf(hands.limit()));
  EXPECT_TRUE(hands.recording().empty());
  EXPECT_FALSE(track.motion(Hand::Right, 1.0));
}

TEST(LiveHands, SamplesLeadTheSimulationAndLimitIsTheSampleBeforeTheLast) {
  LiveHands hands(TrackPolicy{}, {}, margin);
  HandTrack track;
  hands.set(Hand::Right, at(0.1, 1.0, 0.3));
  hands.sample(0.0, ahead, track);
  EXPECT_DOUBLE_EQ(hands.limit(), LiveHands::lead - margin);  // one sample: its own time
  hands.sample(0.03, ahead, track);
  EXPECT_DOUBLE_EQ(hands.limit(), LiveHands::lead - margin);  // the sample before the last
  // No time passed (a run that cannot keep up, sitting at the limit): a knot one spacing (the
  // larger of the margin and lead / 100) after the last, so that the limit moves on.
  hands.sample(0.03, ahead, track);
  const double spacing = std::max(margin, LiveHands::lead / 100);
  EXPECT_DOUBLE_EQ(hands.limit(), 0.03 + LiveHands::lead - margin);
  hands.sample(0.06, ahead, track);
  EXPECT_DOUBLE_EQ(hands.limit(), 0.03 + LiveHands::lead + spacing - margin);
  const auto frames = hands.recording();
  ASSERT_EQ(frames.size(), 4u);
  EXPECT_DOUBLE_EQ(frames[2].t, 0.03 + LiveHands::lead + spacing);
  EXPECT_DOUBLE_EQ(frames[3].t, 0.06 + LiveHands::lead);
  const auto m = track.motion(Hand::Right, 0.12);
  ASSERT_TRUE(m);
  EXPECT_TRUE(m->available);
  EXPECT_EQ(m->position, Vec3(0.1, 1.0, 0.3));
}

// A run slower than the wall clock advances to limit() every turn and then samples again at
// the same time: it must keep moving, not stop for good at the second sample's limit.
TEST(LiveHands, ARunAtTheLimitKeepsMoving) {
  LiveHands hands(TrackPolicy{}, {}, margin);
  HandTrack track;
  hands.set(Hand::Right, at(0.1, 1.0, 0.3));
  double now = 0.0;
  for (int turn = 0; turn < 40; ++turn) {
    hands.sample(now, ahead, track);
    ASSERT_GE(hands.limit(), now) << "turn " << turn;
    now = hands.limit();  // as far as the hands allow, no overshoot
  }
  // About lead - margin every two turns.
  EXPECT_GT(now, 20 * (LiveHands::lead - 2 * margin) - LiveHands::lead);
}

// The invariant the live loop relies on: after each new sample the track is bit-identical to
// the previous one up to the previous limit (plus the margin the loop may overshoot by).
TEST(LiveHands, NewSampleLeavesTheTrackBeforeTheLimitUnchanged) {
  TrackPolicy policy;
  policy.smoothing.filter = SmoothingFilter::OneEuro;  // causal: must not break the invariant
  LiveHands hands(policy, {}, margin);
  HandTrack before, after;
  double now = 0.0, previous_limit = 0.0;
  hands.set(Hand::Left, at(0.0, 1.0, 0.2));
  for (int k = 0; k < 40; ++k) {
    hands.set(Hand::Right, at(0.1 * std::sin(0.7 * k), 1.0 + 0.05 * std::cos(1.3 * k), 0.3));
    if (k == 20) hands.set(Hand::Left, std::nullopt);  // the left hand is lost: a gap
    hands.sample(now, ahead, after);
    if (k > 0) {
      const double limit = previous_limit + margin;
      for (double t = 0.0; t <= limit; t += 0.0037)
        for (const Hand h : {Hand::Left, Hand::Right}) {
          const auto a = before.motion(h, t), b = after.motion(h, t);
          ASSERT_EQ(a.has_value(), b.has_value()) << "t = " << t;
          if (!a) continue;
          EXPECT_EQ(a->available, b->available) << "t = " << t;
          EXPECT_EQ(a->position, b->position) << "t = " << t;
          EXPECT_EQ(a->velocity, b->velocity) << "t = " << t;
        }
    }
    before = after;
    previous_limit = hands.limit();
    now += 0.021 + 0.02 * (k % 3);  // uneven steps, as the wall clock gives them
    now = std::min(now, hands.limit());
  }
}

// The live loop (LiveSession::run) with fixed steps longer than its 1/30 s turn: each turn wants
// to reach min(wall clock, now + 1/30 s), the hands' limit bounds it, and the advance ends on
// the first step at or past it. The hand's frames must stay within lead plus a spacing of the
// simulation (a frame a step ahead on every turn let a hand's latency grow without bound), and
// the run must keep up with the wall clock.
TEST(LiveHands, FramesStayNearTheSimulationWhenItsStepIsLongerThanATurn) {
  for (const double dt : {0.05, 0.055, 0.07, 0.09, 0.1, 0.25}) {
    LiveHands hands(TrackPolicy{}, {}, dt);
    HandTrack track;
    hands.set(Hand::Right, at(0.1, 1.0, 0.3));
    constexpr double turn = 1.0 / 30.0;
    double now = 0.0, wall = 0.0;
    for (int k = 0; k < 600; ++k, wall += turn) {
      hands.set(Hand::Right, at(0.1, 1.0 + 0.05 * std::sin(0.3 * k), 0.3));  // a moving hand
      const double wanted = std::min(wall, now + turn);
      hands.sample(now, wanted, track);
      const double target = std::min(wanted, hands.limit());
      if (target > now) now += dt * std::ceil((target - now) / dt - 1e-9);
      const double last_frame = hands.recording().back().t;
      ASSERT_LE(last_frame - now, LiveHands::lead + 2 * dt + 1e-9) << "dt " << dt << ", turn " << k;
    }
    EXPECT_GT(now, wall - LiveHands::lead - 3 * dt) << "dt " << dt;
    // No frame closer than a spacing to the last: one 4e-17 s after it (the rounding of
    // now + lead) was left out on every turn, and the run stopped.
    EXPECT_TRUE(hands.left_out().empty()) << "dt " << dt << ": " << hands.left_out().front();
  }
}

// A hand taken away (POST /hand with "tracked": false, a sensor that lost it) limits nothing:
// it comes back only in a new run, more than max_gap after its last sample, so its old curve
// never changes, and it cannot hold the loop at its sample before the last for good.
TEST(LiveHands, AHandTakenAwayLimitsNothingAndComesBackInANewRun) {
  TrackPolicy policy;
  policy.max_gap = 0.15;
  LiveHands hands(policy, {}, margin);
  HandTrack track;
  hands.set(Hand::Right, at(0.0, 1.0, 0.3));
  hands.sample(0.0, ahead, track);   // a sample at 0.1
  hands.sample(0.05, ahead, track);  // and at 0.15
  EXPECT_DOUBLE_EQ(hands.limit(), LiveHands::lead - margin);
  hands.set(Hand::Right, std::nullopt);
  hands.sample(0.1, ahead, track);  // no hand: no frame, no limit
  EXPECT_TRUE(std::isinf(hands.limit()));
  hands.set(Hand::Right, at(0.2, 1.0, 0.3));
  hands.sample(0.19, ahead, track);  // 0.29 is within max_gap of 0.15: not yet a new run
  EXPECT_EQ(hands.recording().size(), 2u);
  EXPECT_TRUE(std::isinf(hands.limit()));
  hands.sample(0.21, ahead, track);  // 0.31: a new run, limited by its one sample
  ASSERT_EQ(hands.recording().size(), 3u);
  EXPECT_DOUBLE_EQ(hands.recording().back().t, 0.21 + LiveHands::lead);
  EXPECT_EQ(track.runs(Hand::Right), 2u);
  EXPECT_DOUBLE_EQ(hands.limit(), 0.21 + LiveHands::lead - margin);
  EXPECT_EQ(track.motion(Hand::Right, 0.25)->position, Vec3(0.0, 1.0, 0.3));  // the old run's end
}

// The live loop with both hands taken away keeps up with the wall clock.
TEST(LiveHands, ARunWhoseHandsAreTakenAwayKeepsMoving) {
  LiveHands hands(TrackPolicy{}, {}, margin);
  HandTrack track;
  hands.set(Hand::Left, at(-0.1, 1.0, 0.3));
  hands.set(Hand::Right, at(0.1, 1.0, 0.3));
  double now = 0.0;
  for (int turn = 0; turn < 90; ++turn) {  // 3 s of 1/30 s turns
    if (turn == 10) hands.set(Hand::Left, std::nullopt);
    if (turn == 12) hands.set(Hand::Right, std::nullopt);
    hands.sample(now, ahead, track);
    now = std::min(now + 1.0 / 30, hands.limit());
  }
  EXPECT_DOUBLE_EQ(now, 90.0 / 30);
}

// A hand that jumps 9.9 m between frames 1 ms apart (a run at the limit takes its frame one
// spacing after the last) would give the last sample a tangent of 9600 m/s that throws the
// curve before it 47 m out: that frame is left out with its reason, the track stays within the
// scene bound, and the jump enters at the next turn's wider spacing.
TEST(LiveHands, AFrameThatThrowsTheCurveOutOfTheSceneIsLeftOut) {
  LiveHands hands(TrackPolicy{}, {}, margin);
  HandTrack track;
  hands.set(Hand::Right, at(0.0, 1.0, 0.3));
  hands.sample(0.0, ahead, track);     // 0.1
  hands.sample(0.0333, ahead, track);  // 0.1333
  hands.set(Hand::Right, at(9.9, 1.0, 0.3));
  hands.sample(0.0333, ahead, track);  // at the limit: 0.1343, 9.9 m in 1 ms
  EXPECT_EQ(hands.recording().size(), 2u);
  ASSERT_EQ(hands.left_out().size(), 1u);
  EXPECT_NE(hands.left_out()[0].find("t = 0.1343"), std::string::npos) << hands.left_out()[0];
  EXPECT_NE(hands.left_out()[0].find("right hand's curve between t = 0.1 s and t = 0.1333 s"),
            std::string::npos) << hands.left_out()[0];
  EXPECT_NE(hands.left_out()[0].find("it must stay within +-10 m"), std::string::npos);
  EXPECT_FALSE(track.curve_bound_violation());
  EXPECT_DOUBLE_EQ(hands.limit(), 0.1 - margin);  // the frames that stayed
  hands.sample(0.0666, ahead, track);  // 0.1666: 9.9 m in 33 ms
  EXPECT_EQ(hands.recording().size(), 3u);
  EXPECT_EQ(hands.left_out().size(), 1u);
  EXPECT_FALSE(track.curve_bound_violation());
  EXPECT_EQ(track.motion(Hand::Right, 0.0666 + LiveHands::lead)->position.x(), 9.9);
}

// A run slower than the wall clock (0.5 ms of scene time a turn) samples a spacing after the
// last frame every turn; a hand that moves 9.5 m throws the curve out at that spacing, and at
// the same spacing the frame would be left out on every turn while the track held the run at
// its limit, which would stop it there for good (`drapelab live`). Spaced
// wider each time, the frame is taken after a few turns and the run moves on.
TEST(LiveHands, ARunHeldByAFrameLeftOutMovesOn) {
  LiveHands hands(TrackPolicy{}, {}, margin);
  HandTrack track;
  hands.set(Hand::Right, at(0.0, 1.0, 0.3));
  double now = 0.0;
  for (int turn = 0; turn < 300; ++turn) {
    if (turn == 10) hands.set(Hand::Right, at(9.5, 1.0, 0.3));
    hands.sample(now, ahead, track);
    ASSERT_FALSE(track.curve_bound_violation()) << "turn " << turn;
    now = std::min(now + 5e-4, hands.limit());
  }
  ASSERT_FALSE(hands.left_out().empty());
  EXPECT_LE(hands.left_out().size(), 12u) << hands.left_out().back();
  EXPECT_DOUBLE_EQ(now, 300 * 5e-4);  // held at 0.1078 s before
  EXPECT_EQ(track.motion(Hand::Right, now + LiveHands::lead)->position.x(), 9.5);
}

TEST(LiveHands, RecordingMergesKeysIntoFramesInTimeOrder) {
  HandFrame scene_key;
  scene_key.t = 0.5;
  scene_key.keys = {"m"};
  LiveHands hands(TrackPolicy{}, {scene_key}, margin);
  HandTrack track;
  hands.set(Hand::Right, at(0.0, 1.0, 0.3));
  hands.sample(0.0, ahead, track);  // a frame at 0.1
  hands.add_key(0.1, "r");   // at the frame's time: merged into it
  hands.add_key(0.05, "a");
  hands.sample(0.02, ahead, track);  // a frame at 0.12
  const auto frames = hands.recording();
  ASSERT_EQ(frames.size(), 4u);
  EXPECT_DOUBLE_EQ(frames[0].t, 0.05);
  EXPECT_EQ(frames[0].keys, std::vector<std::string>{"a"});
  EXPECT_TRUE(frames[1].right);
  EXPECT_EQ(frames[1].keys, std::vector<std::string>{"r"});
  EXPECT_DOUBLE_EQ(frames[2].t, 0.12);
  EXPECT_EQ(frames[3].keys, std::vector<std::string>{"m"});
  ASSERT_EQ(track.keys().size(), 3u);
  EXPECT_EQ(track.keys()[0].key, "a");
  EXPECT_EQ(track.keys()[2].key, "m");
}

}  // namespace
}  // namespace drape
