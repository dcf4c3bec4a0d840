#include "experiments/live/live_hands.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>

#include "core/input/input_config.hpp"
#include "integrators/interface/integrator_options.hpp"

namespace drape {

namespace {

const std::optional<HandSample>& sample_of(const HandFrame& frame, Hand hand) {
  return hand == Hand::Left ? frame.left : frame.right;
}

}  // namespace

LiveHands::LiveHands(TrackPolicy policy, std::vector<HandFrame> keys, double margin)
    : m_policy(policy), m_keys(std::move(keys)), m_margin(margin) {}

void LiveHands::set(Hand hand, std::optional<HandSample> sample) {
  std::lock_guard<std::mutex> lock(m_mutex);
  m_latest[hand == Hand::Left ? 0 : 1] = sample;
}

void LiveHands::add_key(double t, const std::string& key) {
  HandFrame frame;
  frame.t = t;
  frame.keys = {key};
  m_keys.push_back(std::move(frame));
}

bool LiveHands::usable(const HandFrame& frame, Hand hand) const {
  const auto& s = sample_of(frame, hand);
  return s && !(s->inferred && m_policy.inferred == InferredPolicy::Drop);
}

const HandFrame* LiveHands::last_usable(Hand hand) const {
  const auto usable = [&](const HandFrame& f) { return this->usable(f, hand); };
  const auto last = std::find_if(m_frames.rbegin(), m_frames.rend(), usable);
  return last == m_frames.rend() ? nullptr : &*last;
}

// A new sample of a hand changes the interpolation back to the sample before its last one (the
// tangent at the last sample, docs/input.md "Interpolation"), unless it starts a new run, which
// it must once the last sample is max_gap older than any later sample can be. A hand that is
// gone comes back only in a new run (sample()), so it limits nothing.
double LiveHands::hand_limit(Hand hand, double next_sample) const {
  constexpr double infinity = std::numeric_limits<double>::infinity();
  const HandFrame* last = last_usable(hand);
  if (!last || m_gone[index(hand)] || next_sample - last->t >= m_policy.max_gap) return infinity;
  const auto usable = [&](const HandFrame& f) { return this->usable(f, hand); };
  const auto from = std::make_reverse_iterator(m_frames.begin() + (last - m_frames.data()));
  const auto before = std::find_if(from, m_frames.rend(), usable);
  if (before == m_frames.rend() || last->t - before->t > m_policy.max_gap) return last->t;
  return before->t;
}

void LiveHands::sample(double now, double wanted, HandTrack& track) {
  constexpr double infinity = std::numeric_limits<double>::infinity();
  // Frames at least a spacing apart: closer ones give the curve tangents that throw it far out
  // (a frame 4e-17 s after the last, the rounding of now + lead, was left out on every turn and
  // froze the run).
  // After frames left out (their curve left the scene), the next one is spaced wider, doubling
  // each time: at the same spacing the same frame would be left out on every turn while the
  // track held the run at its limit, freezing it for as long as the hand stayed. A gap beyond
  // max_gap starts a new run of samples, which bends nothing.
  const double spacing =
      std::max(m_margin, lead / 100) * std::ldexp(1.0, std::min(m_refused, 30));
  HandFrame frame;
  frame.t = now + lead;
  if (!m_frames.empty() && frame.t < m_frames.back().t + spacing) {
    // The last frame is less than a spacing before now + lead: a run that cannot keep up, or one whose step
    // (the margin) is longer than the lead. If the track lets the loop go where it wants, no
    // frame: the latest hands wait for a later turn, so that frames never run ahead of the
    // simulation by more than lead plus a spacing (a frame a spacing ahead on every 1/30 s turn
    // outran a run of steps above 1/30 s without bound). If the track holds the loop back,
    // (limit() = the frame before the last, minus the margin), a frame a spacing after the last
    // moves the limit on; without it a run at the limit would stop for good.
    // The track is rebuilt either way: it takes the keys added since the last turn.
    frame.t = m_limit >= wanted ? -infinity : m_frames.back().t + spacing;
  }
  std::optional<HandSample> latest[2];
  {
    std::lock_guard<std::mutex> lock(m_mutex);
    latest[0] = m_latest[0];
    latest[1] = m_latest[1];
  }
  for (const Hand hand : {Hand::Left, Hand::Right}) {
    const std::size_t h = index(hand);
    if (!latest[h]) {
      // Gone: its next sample, whenever it comes back, must not bend the curve the simulation
      // may already have passed, so it is taken only where it starts a new run (more than
      // max_gap after the hand's last sample). Without this a hand taken away held the
      // simulation at its sample before the last for good (a run with no hand stopped).
      m_gone[h] = last_usable(hand) != nullptr;
    } else if (m_gone[h]) {
      const HandFrame* last = last_usable(hand);
      if (!last || frame.t - last->t > m_policy.max_gap)
        m_gone[h] = false;
      else
        latest[h].reset();  // back too soon: it waits for a later turn
    }
  }
  if (frame.t > -infinity) {
    frame.left = latest[0];
    frame.right = latest[1];
  }
  // Only frames that say something (their times increase: the track needs distinct knots).
  const bool added = frame.left || frame.right;
  if (added) m_frames.push_back(std::move(frame));
  track = HandTrack(m_frames, SensorTransform{}, TimeMap{}, m_policy);
  if (added) {
    // Each position is within the scene bound (POST /hand, the bridge), but two far apart and
    // close in time throw the curve far out between its samples, as in a recording (input.md,
    // Ranges): such a frame is left out, the latest hands wait for a later, wider-spaced turn.
    if (auto violation = track.curve_bound_violation()) {
      m_left_out.push_back(
          fmt::format("t = {} s: {}", nlohmann::json(m_frames.back().t).dump(), *violation));
      m_frames.pop_back();
      track = HandTrack(m_frames, SensorTransform{}, TimeMap{}, m_policy);
      ++m_refused;
    } else {
      m_refused = 0;
    }
  }
  track.add_keys(m_keys, TimeMap{});
  const double next = m_frames.empty() ? now : m_frames.back().t;
  m_limit = std::min(hand_limit(Hand::Left, next), hand_limit(Hand::Right, next)) - m_margin;
}

std::vector<HandFrame> LiveHands::recording() const {
  std::vector<HandFrame> all = m_frames;
  for (const HandFrame& key : m_keys) {
    auto at = std::lower_bound(all.begin(), all.end(), key.t,
                               [](const HandFrame& f, double t) { return f.t < t; });
    if (at != all.end() && at->t == key.t)
      at->keys.insert(at->keys.end(), key.keys.begin(), key.keys.end());
    else
      all.insert(at, key);
  }
  return all;
}

std::unique_ptr<LiveHands> live_hands_for(HandInput& input, const IntegratorOptions& options) {
  std::vector<HandFrame> keys;
  for (const KeyEvent& k : input.track.keys()) {
    keys.emplace_back();
    keys.back().t = k.t;
    keys.back().keys = {k.key};
  }
  // The loop may end a step past its target by up to one step (Simulation::advance); an
  // adaptive method's steps are not known ahead, 10 ms is taken for them (docs/live.md).
  const double margin = options.adaptive ? 0.01 : options.dt;
  auto hands = std::make_unique<LiveHands>(input.config.track, std::move(keys), margin);
  hands->sample(0.0, 0.0, input.track);
  return hands;
}

}  // namespace drape
