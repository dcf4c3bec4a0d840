#pragma once
// The one state layout of drapelab: y = [x; v], 6N doubles. Positions first, then velocities,
// each interleaved per particle (x0 y0 z0 x1 y1 z1 ...). Every module views it through these
// maps instead of copying.
#include <Eigen/Core>

namespace drape {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using VecMap = Eigen::Map<Eigen::VectorXd>;
using ConstVecMap = Eigen::Map<const Eigen::VectorXd>;
/// Parameter types that take vectors, maps and contiguous segments without copying.
using VecRef = Eigen::Ref<Eigen::VectorXd>;
using ConstVecRef = Eigen::Ref<const Eigen::VectorXd>;

/// Number of doubles in the state of n particles.
inline Eigen::Index state_size(Eigen::Index n) { return 6 * n; }

/// Positions block of a state vector (3N values).
inline auto positions(Eigen::VectorXd& y) { return y.head(y.size() / 2); }
inline auto positions(const Eigen::VectorXd& y) { return y.head(y.size() / 2); }
/// Velocities block of a state vector (3N values).
inline auto velocities(Eigen::VectorXd& y) { return y.tail(y.size() / 2); }
inline auto velocities(const Eigen::VectorXd& y) { return y.tail(y.size() / 2); }

/// The 3-vector of particle i inside a 3N block.
template <class Block>
inline auto particle(Block&& block, Eigen::Index i) {
  return block.template segment<3>(3 * i);
}

}  // namespace drape
