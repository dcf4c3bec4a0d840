#include "core/input/hand_track.hpp"

#include <Eigen/LU>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace drape {
namespace {

constexpr double rotation_tolerance = 1e-6;
constexpr double pi = 3.14159265358979323846;

// Smoothing factor of a first-order low-pass filter with cutoff `cutoff` Hz over a step dt.
double low_pass_alpha(double cutoff, double dt) {
  const double tau = 1.0 / (2.0 * pi * cutoff);
  return 1.0 / (1.0 + tau / dt);
}

// Tangents of one run [begin, end) of samples: the derivative at each sample of the parabola
// through it and its two neighbours (the two nearest at the ends). This makes the Hermite
// curve reproduce quadratic motion exactly, so a hand moving with constant acceleration gives
// a held particle the exact p'' of docs/model.md section 5; unlike a global spline, a sample only moves the
// curve over the two intervals on either side of it.
void run_tangents(const std::vector<double>& t, const std::vector<Vec3>& p, std::size_t begin,
                  std::size_t end, std::vector<Vec3>& m) {
  const std::size_t n = end - begin;
  if (n == 1) {
    m[begin] = Vec3::Zero();
    return;
  }
  const auto h = [&](std::size_t k) { return t[k + 1] - t[k]; };
  const auto d = [&](std::size_t k) -> Vec3 { return (p[k + 1] - p[k]) / h(k); };
  if (n == 2) {
    m[begin] = m[begin + 1] = d(begin);
    return;
  }
  for (std::size_t k = begin + 1; k + 1 < end; ++k)
    m[k] = (h(k) * d(k - 1) + h(k - 1) * d(k)) / (h(k - 1) + h(k));
  const std::size_t a = begin;
  m[a] = d(a) - h(a) * (d(a + 1) - d(a)) / (h(a) + h(a + 1));
  const std::size_t z = end - 1;
  m[z] = d(z - 1) + h(z - 1) * (d(z - 1) - d(z - 2)) / (h(z - 2) + h(z - 1));
}

// Cubic Hermite segment from (t0, p0, m0) to (t1, p1, m1) and its first two derivatives. The
// Hermite basis gives p0 and p1 exactly at s = 0 and 1 (its weights are exactly 0 and 1 there),
// so the curve passes through the samples to the bit; a power basis would not.
HandMotion hermite(double t0, double t1, const Vec3& p0, const Vec3& p1, const Vec3& m0,
                   const Vec3& m1, double t) {
  const double h = t1 - t0;
  const double s = (t - t0) / h;
  const double s2 = s * s;
  const double s3 = s2 * s;
  HandMotion out;
  out.available = true;
  out.position = (2 * s3 - 3 * s2 + 1) * p0 + (s3 - 2 * s2 + s) * h * m0 +
                 (-2 * s3 + 3 * s2) * p1 + (s3 - s2) * h * m1;
  out.velocity = ((6 * s2 - 6 * s) * p0 + (3 * s2 - 4 * s + 1) * h * m0 +
                  (-6 * s2 + 6 * s) * p1 + (3 * s2 - 2 * s) * h * m1) /
                 h;
  out.acceleration = ((12 * s - 6) * p0 + (6 * s - 4) * h * m0 + (-12 * s + 6) * p1 +
                      (6 * s - 2) * h * m1) /
                     (h * h);
  return out;
}

}  // namespace

void check_rotation(const Mat3& r, const std::string& file, const std::string& field) {
  const double orthogonality = (r.transpose() * r - Mat3::Identity()).cwiseAbs().maxCoeff();
  if (!(orthogonality <= rotation_tolerance))
    throw InputError(file, field,
                     "not a rotation: R^T R differs from the identity by " +
                         std::to_string(orthogonality));
  if (!(std::abs(r.determinant() - 1.0) <= rotation_tolerance))
    throw InputError(file, field,
                     "not a rotation: determinant " + std::to_string(r.determinant()) +
                         " (a reflection would make the scene frame left-handed)");
}

void check_hand_position(const Vec3& position, const std::string& file, const std::string& field) {
  for (int k = 0; k < 3; ++k)
    if (!(std::abs(position[k]) <= max_hand_coordinate))  // NaN fails too
      throw InputError(file, field + "." + "xyz"[k],
                       fmt::format("{} is not a scene coordinate within +-{} m", position[k],
                                   max_hand_coordinate));
}

void check_hand_positions(const std::vector<HandFrame>& frames, const SensorTransform& transform,
                          const std::string& file,
                          const std::function<std::string(std::size_t)>& frame_field) {
  for (std::size_t i = 0; i < frames.size(); ++i) {
    if (frames[i].left)
      check_hand_position(transform.point(frames[i].left->position), file, frame_field(i) + ".left");
    if (frames[i].right)
      check_hand_position(transform.point(frames[i].right->position), file,
                          frame_field(i) + ".right");
  }
}

HandTrack::HandTrack(const std::vector<HandFrame>& frames, const SensorTransform& transform,
                     const TimeMap& time, const TrackPolicy& policy) {
  if (!(time.scale > 0.0)) throw std::invalid_argument("HandTrack: time scale must be positive");
  if (!(policy.max_gap >= 0.0)) throw std::invalid_argument("HandTrack: negative max_gap");
  for (std::size_t i = 1; i < frames.size(); ++i)
    if (!(frames[i].t > frames[i - 1].t))
      throw std::invalid_argument("HandTrack: frame times must increase strictly");

  for (const Hand hand : {Hand::Left, Hand::Right}) {
    std::vector<double> t;
    std::vector<Vec3> p;
    for (const auto& frame : frames) {
      const auto& sample = hand == Hand::Left ? frame.left : frame.right;
      if (!sample) continue;
      if (sample->inferred && policy.inferred == InferredPolicy::Drop) continue;
      t.push_back(frame.t);
      p.push_back(transform.point(sample->position));
    }
    Curve built = build_curve(t, p, policy);
    for (double& ti : built.t) ti = time.scene(ti);
    for (Vec3& mi : built.m) mi /= time.scale;
    (hand == Hand::Left ? m_left : m_right) = std::move(built);
  }
  add_keys(frames, time);
}

HandTrack::Curve HandTrack::build_curve(const std::vector<double>& t,
                                        const std::vector<Vec3>& p,
                                        const TrackPolicy& policy) {
  // Gaps and smoothing are judged in recording time: whether a gap is a dropped frame or a
  // lost hand, and how fast the sensor jitters, are properties of the sensor, not of playback.
  Curve curve;
  curve.t = t;
  curve.p = p;
  curve.m.assign(p.size(), Vec3::Zero());
  for (std::size_t k = 1; k <= t.size(); ++k)
    if (k == t.size() || t[k] - t[k - 1] > policy.max_gap) curve.run_end.push_back(k);

  std::size_t begin = 0;
  for (const std::size_t end : curve.run_end) {
    if (policy.smoothing.filter == SmoothingFilter::OneEuro) {
      // Restarted at every run: a filter carried across a lost hand would drag the hand
      // from where it disappeared to where it came back.
      const std::vector<double> run_t(t.begin() + begin, t.begin() + end);
      const std::vector<Vec3> run_p(p.begin() + begin, p.begin() + end);
      const auto smooth = detail::one_euro(run_t, run_p, policy.smoothing);
      std::copy(smooth.begin(), smooth.end(), curve.p.begin() + begin);
    }
    run_tangents(curve.t, curve.p, begin, end, curve.m);
    begin = end;
  }
  return curve;
}

void HandTrack::add_keys(const std::vector<HandFrame>& frames, const TimeMap& time) {
  for (const auto& frame : frames)
    for (const auto& key : frame.keys) m_keys.push_back({time.scene(frame.t), key});
  std::stable_sort(m_keys.begin(), m_keys.end(),
                   [](const KeyEvent& a, const KeyEvent& b) { return a.t < b.t; });
}

std::optional<HandMotion> HandTrack::motion(Hand hand, double t) const {
  const Curve& c = curve(hand);
  const auto upper = std::upper_bound(c.t.begin(), c.t.end(), t);
  if (upper == c.t.begin()) return std::nullopt;
  const std::size_t k = static_cast<std::size_t>(upper - c.t.begin()) - 1;  // last t_k <= t
  const auto run = std::upper_bound(c.run_end.begin(), c.run_end.end(), k);
  if (k + 1 < *run)
    return hermite(c.t[k], c.t[k + 1], c.p[k], c.p[k + 1], c.m[k], c.m[k + 1], t);

  // k is the last sample of its run: after it the hand is gone and stays where it was seen.
  HandMotion held;
  held.position = c.p[k];
  if (t > c.t[k]) return held;
  const std::size_t run_begin = run == c.run_end.begin() ? 0 : *(run - 1);
  if (run_begin == k) {  // a run of one sample: seen at this instant, with no motion
    held.available = true;
    return held;
  }
  return hermite(c.t[k - 1], c.t[k], c.p[k - 1], c.p[k], c.m[k - 1], c.m[k], t);
}

bool HandTrack::available(Hand hand, double t) const {
  const auto m = motion(hand, t);
  return m && m->available;
}

std::optional<std::pair<double, double>> HandTrack::span(Hand hand) const {
  const Curve& c = curve(hand);
  if (c.t.empty()) return std::nullopt;
  return std::make_pair(c.t.front(), c.t.back());
}

void HandTrack::check_curve_bound(const std::string& file, const std::string& field) const {
  if (const auto violation = curve_bound_violation()) throw InputError(file, field, *violation);
}

std::optional<std::string> HandTrack::curve_bound_violation() const {
  for (const Hand hand : {Hand::Left, Hand::Right}) {
    const Curve& c = curve(hand);
    std::size_t begin = 0;
    for (const std::size_t end : c.run_end) {
      for (std::size_t k = begin; k + 1 < end; ++k) {
        const double h = c.t[k + 1] - c.t[k];
        const auto at = [&](double s) {
          return hermite(c.t[k], c.t[k + 1], c.p[k], c.p[k + 1], c.m[k], c.m[k + 1],
                         c.t[k] + s * h).position;
        };
        for (int d = 0; d < 3; ++d) {
          // The largest |p| is at an end or where p'(s) = 3 a s^2 + 2 b s + m0 = 0 in (0, 1),
          // with a and b p's coefficients of s^3 and s^2 (the tangents scaled by h).
          const double p0 = c.p[k][d], p1 = c.p[k + 1][d], m0 = h * c.m[k][d], m1 = h * c.m[k + 1][d];
          const double a = 2 * p0 + m0 - 2 * p1 + m1, b = -3 * p0 - 2 * m0 + 3 * p1 - m1;
          double peak = std::max(std::abs(p0), std::abs(p1));
          const double disc = b * b - 3 * a * m0;
          if (a != 0.0 && disc >= 0.0) {
            for (const double s : {(-b + std::sqrt(disc)) / (3 * a), (-b - std::sqrt(disc)) / (3 * a)})
              if (s > 0.0 && s < 1.0) peak = std::max(peak, std::abs(at(s)[d]));
          } else if (a == 0.0 && b != 0.0) {
            const double s = -m0 / (2 * b);
            if (s > 0.0 && s < 1.0) peak = std::max(peak, std::abs(at(s)[d]));
          }
          const bool finite = std::isfinite(m0) && std::isfinite(m1) && std::isfinite(peak);
          if (!finite || !(peak <= max_hand_coordinate))
            return fmt::format(
                "the {} hand's curve between t = {} s and t = {} s {} in {} (its samples there "
                "are too close in time for the distance between them); it must stay within +-{} m",
                hand == Hand::Left ? "left" : "right", nlohmann::json(c.t[k]).dump(),
                nlohmann::json(c.t[k + 1]).dump(),
                finite ? fmt::format("reaches {:.6g} m", peak) : "is not finite", "xyz"[d],
                max_hand_coordinate);
        }
      }
      begin = end;
    }
  }
  return std::nullopt;
}

namespace detail {

std::vector<Vec3> one_euro(const std::vector<double>& t, const std::vector<Vec3>& p,
                           const SmoothingOptions& options) {
  std::vector<Vec3> out(p.size());
  if (p.empty()) return out;
  out[0] = p[0];
  Vec3 speed = Vec3::Zero();
  for (std::size_t i = 1; i < p.size(); ++i) {
    const double dt = t[i] - t[i - 1];
    const Vec3 raw_speed = (p[i] - out[i - 1]) / dt;
    speed += low_pass_alpha(options.d_cutoff, dt) * (raw_speed - speed);
    const double cutoff = options.min_cutoff + options.beta * speed.norm();
    out[i] = out[i - 1] + low_pass_alpha(cutoff, dt) * (p[i] - out[i - 1]);
  }
  return out;
}

}  // namespace detail
}  // namespace drape
