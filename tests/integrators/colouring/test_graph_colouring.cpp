#include "integrators/colouring/graph_colouring.hpp"

#include <gtest/gtest.h>

#include "tests/support/test_support.hpp"

namespace drape {
namespace {

SpringList grid_springs(int rows, int cols, bool bending) {
  ClothParams p = testing::small_cloth(rows, cols);
  p.k_bending = bending ? 1.0 : 0.0;
  return build_cloth(p).springs;
}

// Every member in exactly one colour, ascending within it.
void expect_partition(const Colouring& colours, int n) {
  std::vector<int> seen(static_cast<std::size_t>(n), 0);
  for (const auto& colour : colours) {
    EXPECT_TRUE(std::is_sorted(colour.begin(), colour.end()));
    for (int m : colour) ++seen[static_cast<std::size_t>(m)];
  }
  for (int count : seen) EXPECT_EQ(count, 1);
}

TEST(GraphColouring, NoSpringJoinsTwoParticlesOfOneColour) {
  for (bool bending : {false, true}) {
    const SpringList springs = grid_springs(7, 9, bending);
    const Colouring colours = colour_particles(63, springs);
    expect_partition(colours, 63);
    std::vector<int> colour_of(63);
    for (std::size_t c = 0; c < colours.size(); ++c)
      for (int i : colours[c]) colour_of[static_cast<std::size_t>(i)] = static_cast<int>(c);
    for (Eigen::Index e = 0; e < springs.size(); ++e) {
      EXPECT_NE(colour_of[springs.first[e]], colour_of[springs.second[e]]) << "spring " << e;
    }
    // Structural and shear springs make the king's graph: 4 colours suffice and greedy in row
    // order finds them; bending springs (distance 2) add more.
    if (!bending) {
      EXPECT_EQ(colours.size(), 4u);
    }
    EXPECT_LE(colours.size(), bending ? 9u : 4u);
  }
}

TEST(GraphColouring, NoTwoSpringsOfOneColourShareAParticle) {
  const SpringList springs = grid_springs(6, 5, true);
  const Colouring colours = colour_springs(30, springs);
  expect_partition(colours, static_cast<int>(springs.size()));
  for (const auto& colour : colours) {
    std::vector<int> uses(30, 0);
    for (int e : colour) ++uses[springs.first[e]], ++uses[springs.second[e]];
    for (int u : uses) EXPECT_LE(u, 1);
  }
}

}  // namespace
}  // namespace drape
