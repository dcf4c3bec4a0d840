#include "core/input/hand_track.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "core/input/kinect_readers.hpp"
#include "tests/support/input_test_files.hpp"

namespace drape {
namespace {

using test::expect_input_error;

/// Frames with only a right hand at the given times and positions.
std::vector<HandFrame> right_hand(const std::vector<double>& t, const std::vector<Vec3>& p) {
  std::vector<HandFrame> frames(t.size());
  for (std::size_t i = 0; i < t.size(); ++i) {
    frames[i].t = t[i];
    frames[i].right = HandSample{p[i], false};
  }
  return frames;
}

void expect_vec_near(const Vec3& a, const Vec3& b, double tol) {
  EXPECT_LE((a - b).norm(), tol) << "got " << a.transpose() << ", expected " << b.transpose();
}

TEST(SensorTransform, AppliesScaleRotationTranslation) {
  SensorTransform x;
  x.scale = 2.0;
  x.rotation << 0, 0, 1, 0, 1, 0, -1, 0, 0;  // 90 degrees about +y
  x.translation = Vec3(1, 2, 3);
  expect_vec_near(x.point(Vec3(1, 0.5, 0.25)), Vec3(2 * 0.25 + 1, 2 * 0.5 + 2, -2 + 3), 1e-15);
  expect_vec_near(x.vector(Vec3(1, 0, 0)), Vec3(0, 0, -2), 1e-15);
  EXPECT_NO_THROW(check_rotation(x.rotation, "s.json", "input.transform.rotation"));
}

TEST(SensorTransform, RejectsNonRotations) {
  Mat3 skew = Mat3::Identity();
  skew(0, 1) = 0.1;
  expect_input_error([&] { check_rotation(skew, "s.json", "input.transform.rotation"); },
                     {"s.json", "input.transform.rotation", "not a rotation"});
  Mat3 mirror = Mat3::Identity();
  mirror(0, 0) = -1;
  expect_input_error([&] { check_rotation(mirror, "s.json", "input.transform.rotation"); },
                     {"input.transform.rotation", "determinant"});
  expect_input_error([&] { check_rotation(2 * Mat3::Identity(), "s.json", "r"); }, {"r"});
}

TEST(HandTrack, ReproducesQuadraticMotionExactlyOnUnevenTimes) {
  // Three-point tangents are exact for quadratics, and so is the Hermite curve through them.
  const Vec3 a(0.1, -0.2, 2.5), b(0.5, 1.0, -0.25), c(-1.5, 0.75, 2.0);
  const auto p = [&](double t) -> Vec3 { return a + b * t + c * t * t; };
  const std::vector<double> t = {0.0, 0.03, 0.07, 0.1, 0.2, 0.23};
  std::vector<Vec3> samples;
  for (double ti : t) samples.push_back(p(ti));
  const HandTrack track(right_hand(t, samples), {}, {}, {});
  for (double s = 0.0; s <= 0.23; s += 0.0037) {
    const auto m = track.motion(Hand::Right, s);
    ASSERT_TRUE(m && m->available);
    expect_vec_near(m->position, p(s), 1e-13);
    expect_vec_near(m->velocity, b + 2 * c * s, 1e-11);
    expect_vec_near(m->acceleration, 2 * c, 1e-8);
  }
  EXPECT_FALSE(track.motion(Hand::Left, 0.1));
}

TEST(HandTrack, ExactAtSamplesAndC1OnRealData) {
  const Recording r = read_kinect_v2_csv(test::kinect_recording("Ges01_wavehand.csv"));
  const HandTrack track(r.frames, {}, {}, {});
  for (std::size_t i = 0; i < r.frames.size(); ++i) {
    const auto m = track.motion(Hand::Right, r.frames[i].t);
    ASSERT_TRUE(m && m->available);
    EXPECT_EQ(m->position, r.frames[i].right->position);
    if (i > 0 && i + 1 < r.frames.size()) {  // velocity continuous across the sample
      const double e = 1e-9;
      expect_vec_near(track.motion(Hand::Right, r.frames[i].t - e)->velocity, m->velocity,
                      1e-5);
    }
  }
}

TEST(HandTrack, VelocityAndAccelerationMatchFiniteDifferences) {
  const Recording r = read_kinect_v2_csv(test::kinect_recording("Ges03_drawlines.csv"));
  const HandTrack track(r.frames, {}, {}, {});
  const double h = 1e-6;
  for (std::size_t i = 0; i + 1 < r.frames.size(); i += 7) {
    // A time inside an interval, away from the samples where p'' jumps.
    const double t = r.frames[i].t + 0.37 * (r.frames[i + 1].t - r.frames[i].t);
    const auto m = *track.motion(Hand::Right, t);
    const auto plus = *track.motion(Hand::Right, t + h);
    const auto minus = *track.motion(Hand::Right, t - h);
    const Vec3 fd_v = (plus.position - minus.position) / (2 * h);
    const Vec3 fd_a = (plus.velocity - minus.velocity) / (2 * h);
    expect_vec_near(m.velocity, fd_v, 1e-6 * (1 + m.velocity.norm()));
    expect_vec_near(m.acceleration, fd_a, 1e-5 * (1 + m.acceleration.norm()));
  }
}

TEST(HandTrack, TransformAndTimeMapAreApplied) {
  const Recording r = read_kinect_v2_csv(test::kinect_recording("Ges02_balancinghands.csv"));
  SensorTransform x;
  x.scale = 0.5;
  x.rotation = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  x.translation = Vec3(0.1, 1.2, -0.3);
  const TimeMap time{2.0, 1.5};
  const HandTrack raw(r.frames, {}, {}, {});
  const HandTrack mapped(r.frames, x, time, {});
  EXPECT_EQ(mapped.span(Hand::Left)->first, 2.0);
  for (double tau = 0.0; tau < 5.3; tau += 0.0791) {
    const auto a = *raw.motion(Hand::Left, tau);
    const auto b = *mapped.motion(Hand::Left, time.scene(tau));
    ASSERT_TRUE(b.available);
    expect_vec_near(b.position, x.point(a.position), 1e-12);
    expect_vec_near(b.velocity, x.vector(a.velocity) / 1.5, 1e-10);
    expect_vec_near(b.acceleration, x.vector(a.acceleration) / (1.5 * 1.5), 1e-8);
  }
}

TEST(HandTrack, GapsUpToMaxGapAreBridgedLongerOnesAreNot) {
  // Samples every 0.1 s of p = (t, 0, 0) with the frame at 0.3 untracked and nothing from 0.5
  // to 1.0: the first hole is 0.2 s, the second 0.5 s.
  std::vector<HandFrame> frames;
  for (double t : {0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 1.0, 1.1, 1.2}) {
    HandFrame f;
    f.t = t;
    if (t != 0.3) f.right = HandSample{Vec3(t, 0, 0), false};
    frames.push_back(f);
  }
  TrackPolicy policy;
  policy.max_gap = 0.25;
  const HandTrack track(frames, {}, {}, policy);
  EXPECT_FALSE(track.motion(Hand::Right, -0.01));  // never seen yet
  const auto bridged = *track.motion(Hand::Right, 0.3);
  EXPECT_TRUE(bridged.available);
  expect_vec_near(bridged.position, Vec3(0.3, 0, 0), 1e-14);  // linear motion is exact
  EXPECT_TRUE(track.available(Hand::Right, 0.5));
  const auto gone = *track.motion(Hand::Right, 0.7);  // in the long gap: held where last seen
  EXPECT_FALSE(gone.available);
  EXPECT_EQ(gone.position, Vec3(0.5, 0, 0));
  EXPECT_EQ(gone.velocity, Vec3::Zero());
  EXPECT_EQ(gone.acceleration, Vec3::Zero());
  EXPECT_TRUE(track.available(Hand::Right, 1.05));
  expect_vec_near(track.motion(Hand::Right, 1.05)->velocity, Vec3(1, 0, 0), 1e-12);
  const auto after = *track.motion(Hand::Right, 2.0);  // after the end: held at the last sample
  EXPECT_FALSE(after.available);
  EXPECT_EQ(after.position, Vec3(1.2, 0, 0));

  policy.max_gap = 0.15;  // now the 0.2 s hole is not bridged either
  const HandTrack strict(frames, {}, {}, policy);
  EXPECT_FALSE(strict.available(Hand::Right, 0.3));
  EXPECT_EQ(strict.motion(Hand::Right, 0.3)->position, Vec3(0.2, 0, 0));
  EXPECT_TRUE(strict.available(Hand::Right, 0.4));
}

TEST(HandTrack, InferredSamplesAreUsedOrDropped) {
  std::vector<HandFrame> frames;
  for (int i = 0; i < 10; ++i) {
    HandFrame f;
    f.t = 0.1 * i;
    f.left = HandSample{Vec3(i, 0, 0), i >= 3 && i <= 6};
    frames.push_back(f);
  }
  TrackPolicy policy;
  EXPECT_TRUE(HandTrack(frames, {}, {}, policy).available(Hand::Left, 0.45));
  policy.inferred = InferredPolicy::Drop;
  const HandTrack dropped(frames, {}, {}, policy);
  EXPECT_FALSE(dropped.available(Hand::Left, 0.45));  // 0.2 .. 0.7 is a 0.5 s hole
  EXPECT_EQ(dropped.motion(Hand::Left, 0.45)->position, Vec3(2, 0, 0));
  EXPECT_TRUE(dropped.available(Hand::Left, 0.75));
}

TEST(HandTrack, SingleSampleRunIsAvailableOnlyAtItsTime) {
  const HandTrack track(right_hand({1.0}, {Vec3(1, 2, 3)}), {}, {}, {});
  const auto m = *track.motion(Hand::Right, 1.0);
  EXPECT_TRUE(m.available);
  EXPECT_EQ(m.position, Vec3(1, 2, 3));
  EXPECT_EQ(m.velocity, Vec3::Zero());
  EXPECT_FALSE(track.available(Hand::Right, 1.01));
}

TEST(HandTrack, KeysInTimeOrderFromFramesAndAddedEvents) {
  std::vector<HandFrame> frames(3);
  frames[0].t = 0.0;
  frames[1].t = 1.0;
  frames[1].keys = {"a", "r"};
  frames[2].t = 2.0;
  frames[2].keys = {"m"};
  HandTrack track(frames, {}, TimeMap{0.5, 2.0}, {});
  std::vector<HandFrame> extra(1);
  extra[0].t = 0.5;
  extra[0].keys = {"r"};
  track.add_keys(extra, TimeMap{0.5, 2.0});
  const std::vector<KeyEvent> expected = {{1.5, "r"}, {2.5, "a"}, {2.5, "r"}, {4.5, "m"}};
  EXPECT_EQ(track.keys(), expected);
}

TEST(OneEuro, BetaZeroIsAFirstOrderLowPass) {
  // A unit step sampled every dt: with beta = 0 the cutoff is fixed and the filter output is
  // 1 - (1 - alpha)^n, alpha = 1 / (1 + tau / dt), tau = 1 / (2 pi min_cutoff).
  SmoothingOptions o;
  o.filter = SmoothingFilter::OneEuro;
  o.min_cutoff = 2.0;
  o.beta = 0.0;
  const double dt = 1.0 / 30.0;
  std::vector<double> t;
  std::vector<Vec3> p;
  for (int i = 0; i < 20; ++i) {
    t.push_back(i * dt);
    p.push_back(i == 0 ? Vec3::Zero() : Vec3(1, -2, 0.5));
  }
  const auto out = detail::one_euro(t, p, o);
  const double pi = std::acos(-1.0);
  const double alpha = 1.0 / (1.0 + 1.0 / (2 * pi * o.min_cutoff * dt));
  for (int n = 0; n < 20; ++n)
    expect_vec_near(out[n], (1 - std::pow(1 - alpha, n)) * Vec3(1, -2, 0.5), 1e-14);
}

TEST(OneEuro, RemovesJitterAtRestAndIsOffByDefault) {
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 0.005);
  std::vector<double> t;
  std::vector<Vec3> p;
  for (int i = 0; i < 300; ++i) {
    t.push_back(i / 30.0);
    p.push_back(Vec3(0.2, 1.0, 0.3) + Vec3(noise(rng), noise(rng), noise(rng)));
  }
  const auto frames = right_hand(t, p);
  const HandTrack plain(frames, {}, {}, {});
  EXPECT_EQ(plain.motion(Hand::Right, t[100])->position, p[100]);  // no smoothing by default
  TrackPolicy policy;
  policy.smoothing.filter = SmoothingFilter::OneEuro;
  const HandTrack smooth(frames, {}, {}, policy);
  double raw_sq = 0, smooth_sq = 0;
  for (std::size_t i = 100; i < 300; ++i) {
    raw_sq += (p[i] - Vec3(0.2, 1.0, 0.3)).squaredNorm();
    smooth_sq += (smooth.motion(Hand::Right, t[i])->position - Vec3(0.2, 1.0, 0.3)).squaredNorm();
  }
  EXPECT_LT(smooth_sq, 0.1 * raw_sq);
}

TEST(OneEuro, RestartsAfterAGap) {
  // Two runs far apart: the second must start exactly at its first sample, not be dragged
  // from where the hand disappeared.
  TrackPolicy policy;
  policy.smoothing.filter = SmoothingFilter::OneEuro;
  const HandTrack track(
      right_hand({0.0, 0.033, 0.066, 1.0, 1.033}, {Vec3(0, 0, 0), Vec3(0, 0, 0), Vec3(0, 0, 0),
                                                   Vec3(1, 1, 1), Vec3(1, 1, 1)}),
      {}, {}, policy);
  EXPECT_EQ(track.motion(Hand::Right, 1.0)->position, Vec3(1, 1, 1));
  EXPECT_EQ(track.motion(Hand::Right, 1.033)->position, Vec3(1, 1, 1));
}

TEST(HandTrack, RealChickenWingWithInferredDropped) {
  const Recording r = read_kinect_v2_csv(test::kinect_recording("Ges06_chickenwing.csv"));
  TrackPolicy policy;
  const HandTrack use(r.frames, {}, {}, policy);
  policy.inferred = InferredPolicy::Drop;
  const HandTrack drop(r.frames, {}, {}, policy);
  int use_count = 0, drop_count = 0;
  for (double t = 0.0; t < 5.33; t += 0.01) {
    use_count += use.available(Hand::Right, t);
    drop_count += drop.available(Hand::Right, t);
  }
  EXPECT_EQ(use_count, 534);  // the whole recording
  EXPECT_LT(drop_count, use_count / 2);  // 111 of 160 samples were only inferred
}

}  // namespace
}  // namespace drape
