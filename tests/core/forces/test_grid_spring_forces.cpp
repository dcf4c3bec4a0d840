// The spring loop's kernel against the spring formulas of docs/model.md section 4, spring by spring, and its
// SSE2 and AVX builds against each other.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <utility>

#include "core/forces/forces.hpp"
#include "core/forces/grid_spring_forces.hpp"
#include "core/parallel/parallel_for.hpp"
#include "tests/support/test_support.hpp"

namespace drape {
namespace {

// Sum of spring_force + damping_force (forces.hpp) over the listed springs: the reference.
Eigen::VectorXd reference_spring_forces(const Cloth& cloth, const Eigen::VectorXd& x,
                                        const Eigen::VectorXd& v, double c) {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(x.size());
  const SpringList& s = cloth.springs;
  for (Eigen::Index e = 0; e < s.size(); ++e) {
    const int i = s.first[e], j = s.second[e];
    const Vec3 d = particle(x, j) - particle(x, i);
    const Vec3 force = spring_force(d, s.stiffness[e], s.rest[e]) +
                       damping_force(d, particle(v, j) - particle(v, i), c);
    particle(f, i) += force;
    particle(f, j) -= force;
  }
  return f;
}

Eigen::VectorXd interleaved(ConstComponents soa) {
  Eigen::Matrix3Xd points = soa.matrix().transpose();
  return Eigen::Map<Eigen::VectorXd>(points.data(), points.size());
}

// A 7 x 9 cloth (odd row lengths leave packet tails) of every family, stretched and shaken,
// with one spring of each family made degenerate (both ends at one point).
struct ShakenCloth {
  Cloth cloth = build_cloth(testing::small_cloth(7, 9));
  Eigen::VectorXd x, v;
  ShakenCloth() {
    x = testing::jitter(1.1 * cloth.rest_positions, 0.004, 3);
    v = testing::jitter(Eigen::VectorXd::Zero(x.size()), 0.5, 4);
    particle(x, cloth.index(2, 3)) = particle(x, cloth.index(2, 4));  // structural
    particle(x, cloth.index(5, 5)) = particle(x, cloth.index(6, 6));  // shear
    particle(x, cloth.index(0, 0)) = particle(x, cloth.index(0, 2));  // bending
  }
};

TEST(GridSpringForces, EqualTheSpringFormulasSummedSpringBySpring) {
  ShakenCloth s;
  for (const double c : {0.0, 0.05}) {
    GridSpringForces grid(s.cloth);
    const Eigen::VectorXd expected = reference_spring_forces(s.cloth, s.x, s.v, c);
    const Eigen::VectorXd actual = interleaved(grid.evaluate(s.x, s.v, c));
    // Only the order of the sums differs.
    EXPECT_LT((actual - expected).lpNorm<Eigen::Infinity>(),
              1e-14 * expected.lpNorm<Eigen::Infinity>())
        << "c = " << c;
  }
}

TEST(GridSpringForces, ThinGridsHaveOnlyTheSpringsThatFit) {
  // Stencils longer than the grid have no springs; runs shorter than a packet are all tail.
  for (const auto& [rows, cols] : {std::pair{1, 1}, {1, 6}, {6, 1}, {2, 2}, {3, 2}, {2, 5}}) {
    const Cloth cloth = build_cloth(testing::small_cloth(rows, cols));
    const Eigen::VectorXd x = testing::jitter(1.1 * cloth.rest_positions, 0.004, 5);
    const Eigen::VectorXd v = testing::jitter(Eigen::VectorXd::Zero(x.size()), 0.5, 6);
    GridSpringForces grid(cloth);
    const Eigen::VectorXd expected = reference_spring_forces(cloth, x, v, 0.05);
    EXPECT_LE((interleaved(grid.evaluate(x, v, 0.05)) - expected).lpNorm<Eigen::Infinity>(),
              1e-14 * expected.lpNorm<Eigen::Infinity>())
        << rows << " x " << cols;
  }
}

TEST(GridSpringForces, VelocitiesUnreadWithoutSpringDamping) {
  ShakenCloth s;
  GridSpringForces grid(s.cloth);
  const Eigen::VectorXd with_velocity = interleaved(grid.evaluate(s.x, s.v, 0.0));
  Eigen::VectorXd nan_velocity = Eigen::VectorXd::Constant(s.v.size(), std::nan(""));
  EXPECT_EQ(interleaved(grid.evaluate(s.x, nan_velocity, 0.0)), with_velocity);
}

// The threaded loop (a store per spring, then a gather per particle in the one-thread loop's
// order) against the one-thread loop, bit for bit, on a cloth large enough to run threaded,
// with odd row lengths and a degenerate spring of each family.
TEST(GridSpringForces, ThreadedSumsAreTheOneThreadSumsBitForBit) {
  const Cloth cloth = build_cloth(testing::small_cloth(47, 51));
  ASSERT_GE(cloth.size(), threaded_particles_from);
  Eigen::VectorXd x = testing::jitter(1.1 * cloth.rest_positions, 0.004, 7);
  const Eigen::VectorXd v = testing::jitter(Eigen::VectorXd::Zero(x.size()), 0.5, 8);
  particle(x, cloth.index(20, 3)) = particle(x, cloth.index(20, 4));
  particle(x, cloth.index(30, 5)) = particle(x, cloth.index(31, 6));
  particle(x, cloth.index(46, 0)) = particle(x, cloth.index(46, 2));
  const int threads_before = thread_count();
  for (const double c : {0.0, 0.05}) {
    set_thread_count(1);
    GridSpringForces one(cloth);
    const Eigen::ArrayX3d expected = one.evaluate(x, v, c);
    for (const int threads : {2, 3, 4}) {
      set_thread_count(threads);
      GridSpringForces threaded(cloth);
      for (int repeat = 0; repeat < 2; ++repeat) {  // the second reuses the spring buffers
        const Eigen::ArrayX3d actual = threaded.evaluate(x, v, c);
        EXPECT_EQ(std::memcmp(actual.data(), expected.data(), sizeof(double) * actual.size()), 0)
            << threads << " threads, c = " << c;
      }
    }
  }
  set_thread_count(threads_before);
}

TEST(SpringKernel, SseAndAvxBuildsGiveTheSameBits) {
  if (!spring_kernel::has_avx()) GTEST_SKIP() << "this processor has no AVX";
  ShakenCloth s;
  const Eigen::Index n = s.cloth.size();
  Eigen::ArrayX3d x(n, 3), v(n, 3);
  to_components(s.x, x);
  to_components(s.v, v);
  Eigen::ArrayX3d force_sse(n, 3), force_avx(n, 3), row(s.cloth.params.cols, 3);
  const int rows = s.cloth.params.rows, cols = s.cloth.params.cols;
  for (const SpringStencil& stencil : s.cloth.stencils) {
    force_sse.setZero();
    force_avx.setZero();
    spring_kernel::add_sse2(stencil, rows, cols, 0.05, kernel_arrays(x, v, force_sse, row));
    spring_kernel::add_avx(stencil, rows, cols, 0.05, kernel_arrays(x, v, force_avx, row));
    EXPECT_TRUE((force_sse == force_avx).all()) << "stencil (" << stencil.dr << ", " << stencil.dc << ")";
    EXPECT_GT(force_sse.abs().maxCoeff(), 0.0);
  }
}

}  // namespace
}  // namespace drape
