#include "core/manipulations/manipulations.hpp"

#include <fmt/format.h>

#include <limits>

#include "core/manipulations/hold_ramp.hpp"
#include "core/manipulations/hold_search.hpp"
#include "core/manipulations/mapping.hpp"

namespace drape {

namespace {

// Keys due within this of a step's end are applied at that step (fixed steps accumulate
// round-off in t).
constexpr double key_time_eps = 1e-9;

/// A held particle's prescribed motion: the interpolated hand. Where the track has no sample
/// (the hand lost within a step) it stays at `parked`.
class HandTrajectory final : public Trajectory {
 public:
  HandTrajectory(const HandTrack& track, Hand hand, const Vec3& parked)
      : m_track(track), m_hand(hand), m_parked(parked) {}
  Vec3 position(double t) const override {
    const auto m = m_track.motion(m_hand, t);
    return m ? m->position : m_parked;
  }
  Vec3 velocity(double t) const override {
    const auto m = m_track.motion(m_hand, t);
    return m ? m->velocity : Vec3::Zero();
  }
  Vec3 acceleration(double t) const override {
    const auto m = m_track.motion(m_hand, t);
    return m ? m->acceleration : Vec3::Zero();
  }

 private:
  const HandTrack& m_track;
  Hand m_hand;
  Vec3 m_parked;
};

}  // namespace

namespace detail {

/// The state as read, copied only once something changes it.
class StateEdit {
 public:
  explicit StateEdit(const Eigen::VectorXd& original) : m_original(original) {}
  const Eigen::VectorXd& current() const { return m_edited ? *m_edited : m_original; }
  Eigen::VectorXd& edit() {
    if (!m_edited) m_edited = m_original;
    return *m_edited;
  }
  std::optional<Eigen::VectorXd> take() { return std::move(m_edited); }

 private:
  const Eigen::VectorXd& m_original;
  std::optional<Eigen::VectorXd> m_edited;
};

}  // namespace detail

const char* hand_name(Hand hand) { return hand == Hand::Left ? "left" : "right"; }

nlohmann::json ManipulationEvent::to_json(const Cloth& cloth) const {
  nlohmann::json j = {{"t", t}, {"type", type}};
  if (!key.empty()) j["key"] = key;
  if (!hand.empty()) j["hand"] = hand;
  if (particle >= 0) {
    j["particle"] = particle;
    j["row"] = cloth.row_of(particle);
    j["col"] = cloth.col_of(particle);
  }
  if (object_particle >= 0) j["object_particle"] = object_particle;
  if (type == "hold") j["distance"] = value;
  if (type == "attach_fixed") j["attach_error"] = value;
  if (!reason.empty()) j["reason"] = reason;
  return j;
}

Manipulator::Manipulator(ClothSystem& system, const HandTrack* track,
                         const ManipulationParams& params)
    : m_system(system), m_track(track), m_params(params) {
  m_hands = {HandState{Hand::Left}, HandState{Hand::Right}};
}

void Manipulator::copy_state_from(const Manipulator& other) {
  m_hands = other.m_hands;
  m_attaching = other.m_attaching;
  m_next_key = other.m_next_key;
  m_hold_search = other.m_hold_search;
  m_events = other.m_events;
}

double Manipulator::next_key_time(double t) const {
  double next = std::numeric_limits<double>::infinity();
  for (const PendingAttach& a : m_attaching)
    if (a.due > t + key_time_eps) next = std::min(next, a.due);
  if (!m_track) return next;
  for (std::size_t k = m_next_key; k < m_track->keys().size(); ++k)
    if (m_track->keys()[k].t > t + key_time_eps) return std::min(next, m_track->keys()[k].t);
  return next;
}

void Manipulator::ignore_keys_after(double t) {
  if (!m_track) return;
  for (; m_next_key < m_track->keys().size(); ++m_next_key) {
    const KeyEvent& key = m_track->keys()[m_next_key];
    ignore(t, key.key, fmt::format("pressed at scene time {:.6g} s, after the run's end", key.t));
  }
}

void Manipulator::ignore(double t, const std::string& key, const std::string& reason) {
  ManipulationEvent e;
  e.t = t;
  e.type = "ignored";
  e.key = key;
  e.reason = reason;
  m_events.push_back(e);
}

bool Manipulator::a_hand_may_hold() const {
  if (!m_track) return false;
  for (const HandState& h : m_hands)
    if (h.held < 0) return true;
  return false;
}

std::optional<Eigen::VectorXd> Manipulator::update(double t, const Eigen::VectorXd& y) {
  detail::StateEdit state(y);
  bool changed = false;
  finish_attaches(t, state.current(), changed);
  if (m_track) {
    const auto& keys = m_track->keys();
    while (m_next_key < keys.size() && keys[m_next_key].t <= t + key_time_eps) {
      // A key pressed before the run starts (a negative input.time_offset selects a later
      // window of a recording) did not happen in this run: played at t = 0 it would act on a
      // state it was never pressed in. It is listed, not played (docs/input.md, "Time").
      const KeyEvent& key = keys[m_next_key];
      if (key.t < -key_time_eps)
        ignore(t, key.key,
               fmt::format("pressed at scene time {:.6g} s, before the run starts", key.t));
      else
        apply_key(t, key.key, state, changed);
      ++m_next_key;
    }
    update_holds(t, state, changed);
  }
  if (!changed) {
    m_hold_search.finish_update(t, y, m_system.num_particles(), a_hand_may_hold());
    return std::nullopt;
  }
  Eigen::VectorXd& out = state.edit();
  const Eigen::Index n3 = 3 * m_system.num_particles();
  m_system.constraints().project(t, out.head(n3), out.tail(n3));
  m_hold_search.finish_update(t, out, m_system.num_particles(), a_hand_may_hold());
  return state.take();
}

void Manipulator::add_event(double t, const std::string& type, const std::string& key,
                            const HandState* hand, int particle, int object_particle,
                            double value) {
  ManipulationEvent e;
  e.t = t;
  e.type = type;
  e.key = key;
  if (hand) e.hand = hand_name(hand->hand);
  e.particle = particle;
  e.object_particle = object_particle;
  e.value = value;
  m_events.push_back(e);
}

void Manipulator::apply_key(double t, const std::string& key, detail::StateEdit& state,
                            bool& changed) {
  if (key == "r") return release(t, key, changed);
  if (key == "a") return attach(t, key, state, changed);
  if (key == "m") return map(t, key, state, changed);
  ignore(t, key, "no manipulation is bound to this key (r release, a attach, m map)");
}

void Manipulator::release(double t, const std::string& key, bool& changed) {
  ConstraintSet& constraints = m_system.constraints();
  if (m_params.release_held) {
    bool any = false;
    for (HandState& h : m_hands) {
      if (h.held < 0) continue;
      constraints.release(h.held);
      add_event(t, "release", key, &h, h.held);
      let_go(h, t);
      any = true;
    }
    if (!any) return ignore(t, key, "release targets the held particle and nothing is held");
    changed = true;
    return;
  }
  const int i = m_system.cloth().index(m_params.release_pin.row, m_params.release_pin.col);
  if (!constraints.is_fixed(i)) return ignore(t, key, "the release particle is not fixed");
  constraints.release(i);
  HandState* holder = nullptr;
  for (HandState& h : m_hands)
    if (h.held == i) holder = &h;
  if (holder) let_go(*holder, t);
  add_event(t, "release", key, holder, i);
  changed = true;
}

void Manipulator::attach(double t, const std::string& key, detail::StateEdit& state,
                         bool& changed) {
  const Dummy* dummy = m_system.dummy();
  if (!dummy) return ignore(t, key, "attach needs an object and the scene has none");
  bool any = false;
  for (HandState& h : m_hands) {
    if (h.held < 0) continue;
    const Vec3 hand_position = m_system.constraints().trajectory(h.held)->position(t);
    const int o = dummy->nearest(hand_position).index;
    if (o < 0) {  // a non-finite hand has no nearest object particle
      ignore(t, key, "the hand position is not finite");
      continue;
    }
    const int i = h.held;
    m_system.constraints().release(i);
    Eigen::VectorXd& y = state.edit();
    const Eigen::Index n3 = 3 * m_system.num_particles();
    // The particle starts from rest on the object particle; collision pushes it out. With
    // attach_at_contact_distance it starts where collision would leave it (docs/manipulations.md).
    const double lift =
        m_params.attach_at_contact_distance ? m_system.params().collision.threshold : 0.0;
    y.segment<3>(3 * i) = dummy->position(o) + lift * dummy->normal(o);
    y.segment<3>(n3 + 3 * i).setZero();
    add_event(t, "attach", key, &h, i, o);
    let_go(h, t);
    if (m_params.attach_time > 0.0)
      m_attaching.push_back({i, o, std::numeric_limits<int>::max(), t + m_params.attach_time});
    else
      m_attaching.push_back(
          {i, o, m_params.attach_iterations, std::numeric_limits<double>::infinity()});
    any = true;
  }
  if (!any) return ignore(t, key, "attach needs a held particle and nothing is held");
  changed = true;
  if (m_params.attach_iterations == 0 && !(m_params.attach_time > 0.0))
    finish_attaches(t, state.current(), changed);
}

void Manipulator::finish_attaches(double t, const Eigen::VectorXd& y, bool& changed) {
  const Dummy* dummy = m_system.dummy();
  const double delta = m_system.params().collision.threshold;
  for (auto it = m_attaching.begin(); it != m_attaching.end();) {
    // Called once after every step: after attach_iterations steps, or at the time attach_time
    // after the attach (the loop stops there, next_key_time), the particle is fixed.
    const bool due = std::isfinite(it->due) ? t >= it->due - key_time_eps : --it->steps_left <= 0;
    if (!due) {
      ++it;
      continue;
    }
    const int i = it->particle, o = it->object_particle;
    if (m_system.constraints().is_fixed(i)) {
      ManipulationEvent e;
      e.t = t;
      e.type = "ignored";
      e.particle = i;
      e.reason = "attach not completed: the particle was fixed again before its iterations ended";
      m_events.push_back(e);
    } else {
      const Vec3 x = y.segment<3>(3 * i);
      m_system.constraints().fix_at(i, x);
      const Vec3 target = dummy->position(o) + delta * dummy->normal(o);
      add_event(t, "attach_fixed", "", nullptr, i, o, (x - target).norm());
      changed = true;
    }
    it = m_attaching.erase(it);
  }
}

void Manipulator::map(double t, const std::string& key, detail::StateEdit& state,
                      bool& changed) {
  const Dummy* dummy = m_system.dummy();
  if (!dummy) return ignore(t, key, "map needs an object and the scene has none");
  const Cloth& cloth = m_system.cloth();
  ConstraintSet& constraints = m_system.constraints();
  // Mapping lays out the whole cloth anew: every earlier constraint and hold refers to the
  // old layout, so all are dropped before the top row and column 0 are fixed.
  for (const int i : std::vector<int>(constraints.fixed_particles())) constraints.release(i);
  for (HandState& h : m_hands) let_go(h, t);
  m_attaching.clear();
  Eigen::VectorXd& y = state.edit();
  const Eigen::Index n3 = 3 * m_system.num_particles();
  y.head(n3) = map_cloth(cloth, *dummy, m_params.map_top, m_params.map_direction,
                         m_system.params().collision.threshold);
  y.tail(n3).setZero();
  for (int i = 0; i < cloth.size(); ++i)
    if (cloth.row_of(i) == 0 || cloth.col_of(i) == 0) constraints.fix_at(i, y.segment<3>(3 * i));
  add_event(t, "map", key, nullptr, -1);
  changed = true;
}

std::shared_ptr<const Trajectory> Manipulator::hold_trajectory(double t, Hand hand,
                                                                const Vec3& x,
                                                                const Vec3& v) const {
  auto on_hand = std::make_shared<HandTrajectory>(*m_track, hand, x);
  if (m_params.hold_ramp <= 0.0) return on_hand;  // the paper's snap
  return std::make_shared<RampedTrajectory>(std::move(on_hand), x, v, t, m_params.hold_ramp);
}

void Manipulator::update_holds(double t, detail::StateEdit& state, bool& changed) {
  ConstraintSet& constraints = m_system.constraints();
  for (HandState& h : m_hands) {
    auto motion = m_track->motion(h.hand, t);
    if (motion && !motion->available) motion.reset();  // seen before, not now
    if (h.held >= 0) {
      const Vec3 x = state.current().segment<3>(3 * h.held);
      if (!motion && !h.paused) {
        // The hand is lost: the particle stays where it is until the hand is tracked again.
        constraints.fix_at(h.held, x);
        h.paused = true;
        add_event(t, "hold_paused", "", &h, h.held);
        changed = true;
      } else if (motion && h.paused) {
        constraints.fix(h.held, hold_trajectory(t, h.hand, x, Vec3::Zero()));
        h.paused = false;
        add_event(t, "hold_resumed", "", &h, h.held);
        changed = true;
      }
      continue;
    }
    if (!motion) continue;
    double distance = 0.0;
    const int candidate =
        nearest_free_particle(m_system, motion->position, state.current(), distance);
    if (candidate < 0) continue;
    if (!h.armed) {
      // After a release the hand is still at the particle: it must move away before it can
      // hold again, or every release would be undone at once. The hand itself must move: the
      // cloth moving away from a still hand (an attached particle jumping onto the object)
      // would re-arm it, and a neighbour swinging in would be held 2 ms after the attach.
      const double moved = (motion->position - h.let_go).norm();
      h.armed = distance >= m_params.hold_threshold && !(moved < m_params.hold_threshold);
      continue;
    }
    if (distance >= m_params.hold_threshold) continue;
    const int held = m_hold_search.first_reached_particle(m_system, *m_track, h.hand, t,
                                                          state.current(), m_params.hold_threshold);
    h.held = held;
    const Eigen::Index n3 = 3 * m_system.num_particles();
    const Vec3 x = state.current().segment<3>(3 * held);
    constraints.fix(held, hold_trajectory(t, h.hand, x, state.current().segment<3>(n3 + 3 * held)));
    add_event(t, "hold", "", &h, held, -1, (x - motion->position).norm());
    changed = true;
  }
}

void Manipulator::let_go(HandState& h, double t) const {
  h.held = -1;
  h.armed = false;
  h.paused = false;
  const auto motion = m_track ? m_track->motion(h.hand, t) : std::nullopt;
  h.let_go = motion && motion->available ? motion->position
                                         : Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
}

std::vector<HandStatus> Manipulator::hands(double t, const Eigen::VectorXd& y) const {
  std::vector<HandStatus> out;
  for (const HandState& h : m_hands) {
    HandStatus s;
    s.hand = h.hand;
    s.held = h.held;
    const auto motion = m_track ? m_track->motion(h.hand, t) : std::nullopt;
    if (motion && motion->available) {
      s.available = true;
      s.position = motion->position;
      s.candidate = nearest_free_particle(m_system, s.position, y, s.distance);
    }
    out.push_back(s);
  }
  return out;
}

}  // namespace drape
