#pragma once
// Fixed particles (docs/model.md section 5): a constraint x_i = p_i(t) replaces particle i's rows of the
// right-hand side by the prescribed motion, and after every step its position and velocity are
// projected onto p_i(t), p_i'(t). Pins, held particles, attached and mapped particles are all
// fixed particles with different trajectories; this is the one place that applies them.
#include <memory>
#include <vector>

#include "core/state/state.hpp"

namespace drape {

/// A prescribed motion p(t) with its first two derivatives.
class Trajectory {
 public:
  virtual ~Trajectory() = default;
  virtual Vec3 position(double t) const = 0;
  virtual Vec3 velocity(double t) const = 0;
  virtual Vec3 acceleration(double t) const = 0;
};

/// A trajectory that stays at one point (pins, attached and mapped particles).
class FixedPoint final : public Trajectory {
 public:
  explicit FixedPoint(const Vec3& point) : m_point(point) {}
  Vec3 position(double) const override { return m_point; }
  Vec3 velocity(double) const override { return Vec3::Zero(); }
  Vec3 acceleration(double) const override { return Vec3::Zero(); }

 private:
  Vec3 m_point;
};

/// The set of fixed particles, with a dense mask that the hot loops read.
class ConstraintSet {
 public:
  explicit ConstraintSet(int num_particles = 0);

  /// Fixes particle i to a trajectory (replacing any earlier one).
  void fix(int i, std::shared_ptr<const Trajectory> trajectory);
  /// Fixes particle i at a point.
  void fix_at(int i, const Vec3& point);
  /// Frees particle i; no effect when it is not fixed.
  void release(int i);
  bool is_fixed(int i) const { return m_trajectory[i] != nullptr; }
  /// 1 for fixed particles, 0 for free ones.
  const std::vector<unsigned char>& mask() const { return m_mask; }
  /// Indices of the fixed particles, ascending.
  const std::vector<int>& fixed_particles() const { return m_fixed; }
  const Trajectory* trajectory(int i) const { return m_trajectory[i].get(); }

  /// Replaces fixed rows of ydot = [x'; v'] by [p'(t); p''(t)].
  void apply_to_rhs(double t, VecRef x_dot, VecRef v_dot) const;
  /// Projects fixed particles of the state onto p(t), p'(t).
  void project(double t, VecRef x, VecRef v) const;
  /// Zeroes the fixed rows of a 3N vector (filters a search direction or residual).
  void zero_fixed(VecRef values) const;
  /// Largest |p'(t)| over fixed particles at time t (for the runaway bound).
  double max_speed(double t) const;

 private:
  std::vector<std::shared_ptr<const Trajectory>> m_trajectory;
  std::vector<unsigned char> m_mask;
  std::vector<int> m_fixed;  // kept sorted: the loops touch only the fixed particles
};

}  // namespace drape
