// The one state layout (core/state/state.hpp): y = [x; v], 6N doubles, each block interleaved
// per particle; the views write through to the state they view.
#include "core/state/state.hpp"

#include <gtest/gtest.h>

namespace drape {
namespace {

TEST(State, PositionsThenVelocitiesInterleavedPerParticle) {
  EXPECT_EQ(state_size(4), 24);
  Eigen::VectorXd y = Eigen::VectorXd::LinSpaced(24, 0.0, 23.0);
  EXPECT_EQ(positions(y).size(), 12);
  EXPECT_EQ(velocities(y)[0], 12.0);
  EXPECT_EQ(Vec3(particle(positions(y), 2)), Vec3(6.0, 7.0, 8.0));
  EXPECT_EQ(Vec3(particle(velocities(y), 3)), Vec3(21.0, 22.0, 23.0));
  const Eigen::VectorXd& constant = y;
  EXPECT_EQ(positions(constant).data(), y.data()) << "a view, not a copy";
}

TEST(State, ViewsWriteThroughToTheState) {
  Eigen::VectorXd y = Eigen::VectorXd::Zero(12);
  particle(velocities(y), 1) = Vec3(1.0, 2.0, 3.0);
  positions(y).array() += 5.0;
  EXPECT_EQ(y.segment<3>(9), Vec3(1.0, 2.0, 3.0));
  EXPECT_EQ(y.head(6), Eigen::VectorXd::Constant(6, 5.0));
  VecMap x(y.data(), 6);
  particle(x, 0).setZero();
  EXPECT_EQ(y.head(3).norm(), 0.0);
}

}  // namespace
}  // namespace drape
