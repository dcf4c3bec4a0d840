#pragma once
// The cloth-on-dummy model as a constrained ODE (docs/model.md section 5): y = [x; v],
// y' = [v; M^-1 F(x, v)], fixed particles replaced by their prescribed motion and projected
// after every step. The model evaluates; it never owns time or steps.
#include <Eigen/SparseCore>
#include <memory>
#include <vector>

#include "core/cloth/cloth.hpp"
#include "core/collision/collision.hpp"
#include "core/collision/friction.hpp"
#include "core/model/constraints.hpp"
#include "core/dummy/dummy.hpp"
#include "core/forces/grid_spring_forces.hpp"

namespace drape {

/// Forces that are not springs: gravity and collision.
struct ForceParams {
  Vec3 gravity = Vec3(0.0, -9.81, 0.0);
  CollisionParams collision;
};

/// Energy terms of docs/model.md section 4; total = kinetic + spring + gravity + collision.
struct EnergyBreakdown {
  double kinetic = 0.0;
  double spring = 0.0;
  double gravity = 0.0;
  double collision = 0.0;
  /// The lagged friction potential D of a frozen step (section 4.12; 0 otherwise): a
  /// dissipation potential, not stored energy, hence not in the total.
  double friction = 0.0;
  double total() const { return kinetic + spring + gravity + collision; }
};

/// Which forces an evaluation includes, for the IMEX splitting of arkode-imex (docs/model.md
/// section 5): the springs (elastic and spring damping), the collision force, the body forces
/// (gravity and air damping); `kinematics` says whether y' carries x' = v and the fixed
/// particles' prescribed motion (the implicit side of a split does, the explicit side does not).
/// The two sides of a split add up to `all`. `with_smooth_friction` adds the regularised
/// Coulomb force of the current state (friction.hpp, smooth_coulomb_force; nothing with
/// collision.friction = 0), which only a right-hand side without a step start asks for
/// (arkode-*); the other integrators freeze the lagged potential or filter velocities instead.
struct ForceSplit {
  bool with_springs, with_collision, with_body, with_kinematics;
  bool with_smooth_friction = false;

  static const ForceSplit all;
  static const ForceSplit springs;                ///< f_I of the springs-only split
  static const ForceSplit non_springs;            ///< its f_E: collision and body forces
  static const ForceSplit springs_and_collision;  ///< f_I with the contact implicit
  static const ForceSplit body;                   ///< its f_E: gravity and air damping
};
inline constexpr ForceSplit ForceSplit::all{true, true, true, true};
inline constexpr ForceSplit ForceSplit::springs{true, false, false, true};
inline constexpr ForceSplit ForceSplit::non_springs{false, true, true, false};
inline constexpr ForceSplit ForceSplit::springs_and_collision{true, true, false, true};
inline constexpr ForceSplit ForceSplit::body{false, false, true, false};

/// dF/dx and dF/dv as 3x3 blocks in the pair pattern of forces.hpp, for solvers that keep the
/// spring graph's sparsity fixed: spring e (i, j) contributes [-J J; J -J] to rows and columns
/// (i, j); a particle block acts on particle i alone. Fixed particles' rows are not zeroed (a
/// spring block is shared by two rows): callers drop them.
struct JacobianBlocks {
  std::vector<Mat3> spring_x, spring_v;      ///< J = dF_i/dx_j and dF_i/dv_j, one per spring
  std::vector<Mat3> particle_x, particle_v;  ///< dF_i/dx_i and dF_i/dv_i, one per particle
};

/// The constrained cloth ODE: forces, right-hand side, projection, energy and Jacobians.
class ClothSystem {
 public:
  /// `dummy` may be null (no object in the scene).
  ClothSystem(Cloth cloth, std::shared_ptr<const Dummy> dummy, ForceParams params);

  int num_particles() const { return m_cloth.size(); }
  /// Length of the state vector, 6N.
  Eigen::Index size() const { return 6 * static_cast<Eigen::Index>(num_particles()); }
  const Cloth& cloth() const { return m_cloth; }
  const Dummy* dummy() const { return m_dummy.get(); }
  const ForceParams& params() const { return m_params; }
  double particle_mass() const { return m_cloth.params.particle_mass; }
  ConstraintSet& constraints() { return m_constraints; }
  const ConstraintSet& constraints() const { return m_constraints; }
  /// The collision term, whose contact pairing the implicit integrators set (Collision).
  Collision& collision() { return m_collision; }
  const Collision& collision() const { return m_collision; }
  /// The lagged friction potential (docs/model.md section 4.12), frozen by freeze_friction.
  const LaggedFriction& friction() const { return m_friction; }

  /// Freezes the lagged friction of a step of size h from positions x (3N): until
  /// release_friction(), forces(), the Jacobians and energy().friction include it as part of the
  /// collision term. A no-op with collision.friction = 0 or no object.
  void freeze_friction(ConstVecRef x, double h);
  void release_friction() { m_friction.release(); }
  /// Velocity-level Coulomb friction (section 4.12) after a velocity change of duration dt that
  /// included the collision force at x: each free particle's tangential velocity shrinks by
  /// mu dt |F_collision(x)| / m, down to 0. A no-op with collision.friction = 0.
  void apply_velocity_friction(ConstVecRef x, VecRef v, double dt) const;

  /// The grid at rest, at zero velocity, projected onto the constraints at time t.
  Eigen::VectorXd initial_state(double t) const;

  /// Total force F(x, v) on every particle (3N values), fixed particles included.
  void forces(ConstVecRef x, ConstVecRef v, VecRef f) const;
  /// The part of the force that `split` selects; the parts add up to forces().
  void forces(ConstVecRef x, ConstVecRef v, VecRef f, ForceSplit split) const;
  /// M^-1 F for free particles, p''(t) for fixed ones.
  void acceleration(double t, ConstVecRef x, ConstVecRef v, VecRef a) const;
  /// y' = [v; a] with fixed rows replaced by [p'(t); p''(t)].
  void rhs(double t, ConstVecRef y, VecRef y_dot) const;
  /// The part of y' that `split` selects; rhs(springs) + rhs(non_springs) = rhs(all). The
  /// springs part also holds x' = v and the fixed rows [p'(t); p''(t)] (the stiff, implicit part
  /// of arkode-imex); the non-spring part is [0; M^-1 F_rest] with zero fixed rows.
  void rhs(double t, ConstVecRef y, VecRef y_dot, ForceSplit split) const;
  /// Penetration correction (a free particle inside the dummy moves onto its nearest object
  /// particle and loses its inward normal velocity), then fixed particles onto p(t), p'(t).
  /// Returns the number of corrected penetrations.
  int project(double t, VecRef x, VecRef v) const;
  /// Energy of the state (velocities must be synchronised with positions).
  EnergyBreakdown energy(ConstVecRef x, ConstVecRef v) const;

  /// out = dF/dx dx + dF/dv dv, with the fixed particles' rows zeroed (their motion is
  /// prescribed). `definite` clamps compressed springs' transverse stiffness (forces.hpp).
  void force_jacobian_times(ConstVecRef x, ConstVecRef v, ConstVecRef dx,
                            ConstVecRef dv, VecRef out, bool definite) const;
  /// The same for the part of the force that `split` selects.
  void force_jacobian_times(ConstVecRef x, ConstVecRef v, ConstVecRef dx,
                            ConstVecRef dv, VecRef out, bool definite, ForceSplit split) const;
  /// Sparse dF/dx and dF/dv (3N x 3N) with the fixed particles' rows zeroed.
  void force_jacobians(ConstVecRef x, ConstVecRef v, bool definite,
                       Eigen::SparseMatrix<double>& dfdx,
                       Eigen::SparseMatrix<double>& dfdv) const;
  /// The same for the part of the force that `split` selects.
  void force_jacobians(ConstVecRef x, ConstVecRef v, bool definite,
                       Eigen::SparseMatrix<double>& dfdx, Eigen::SparseMatrix<double>& dfdv,
                       ForceSplit split) const;
  /// The Jacobian blocks of the forces that `split` selects (every spring, every particle).
  void force_jacobian_blocks(ConstVecRef x, ConstVecRef v, bool definite, ForceSplit split,
                             JacobianBlocks& blocks) const;

 private:
  // forces(), or M^-1 forces() with per_mass (the division fused into the last pass).
  template <bool per_mass>
  void evaluate_forces(ConstVecRef x, ConstVecRef v, VecRef f, ForceSplit split) const;
  /// Spring e's blocks J = dF_i/dx_j and dF_i/dv_j.
  void spring_jacobian_block(ConstVecRef x, ConstVecRef v, bool definite, Eigen::Index e,
                             Mat3& jx, Mat3& jv) const;
  /// dF_i/dx_i of the collision and friction terms that `split` selects.
  Mat3 particle_position_jacobian(ConstVecRef x, bool definite, ForceSplit split, int i) const;
  /// dF_i/dv_i of the air damping, if `split` selects it.
  Mat3 air_jacobian(ForceSplit split) const;
  /// Whether `split` takes the smooth Coulomb force (a friction coefficient and an object).
  bool smooth_friction(ForceSplit split) const;
  /// dF_i/dv_i of the air damping and the smooth Coulomb force that `split` selects.
  Mat3 particle_velocity_jacobian(ConstVecRef x, ConstVecRef v, ForceSplit split, int i,
                                  const Mat3& air) const;
  template <class Visit>
  void for_each_jacobian_block(ConstVecRef x, ConstVecRef v, bool definite, ForceSplit split,
                               Visit&& visit) const;

  Cloth m_cloth;
  std::shared_ptr<const Dummy> m_dummy;
  Collision m_collision;
  LaggedFriction m_friction;
  // Scratch of the spring loop: mutable so that force evaluation stays a const query (a system
  // is never shared between callers on different threads; its loops thread themselves).
  mutable GridSpringForces m_spring_forces;
  ForceParams m_params;
  ConstraintSet m_constraints;
};

}  // namespace drape
