// Grid geometry and spring families of docs/model.md section 2.
#include <gtest/gtest.h>

#include <map>

#include "core/cloth/cloth.hpp"
#include "tests/support/test_support.hpp"

namespace drape {
namespace {

TEST(Cloth, ParticlesSitOnTheGridOfSpec2) {
  ClothParams p = testing::small_cloth(3, 4);
  p.origin = Vec3(0.1, 1.2, 0.3);
  p.col_dir = Vec3(0, 0, 1);
  p.row_dir = Vec3(1, 0, 0);
  const Cloth cloth = build_cloth(p);
  ASSERT_EQ(cloth.size(), 12);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) {
      const int i = r * 4 + c;
      EXPECT_EQ(cloth.index(r, c), i);
      EXPECT_EQ(cloth.row_of(i), r);
      EXPECT_EQ(cloth.col_of(i), c);
      const Vec3 expected = p.origin + c * 0.02 * p.col_dir + r * 0.02 * p.row_dir;
      EXPECT_TRUE(cloth.rest_positions.segment<3>(3 * i).isApprox(expected, 1e-15));
    }
}

TEST(Cloth, SpringCountsAndRestLengthsPerFamily) {
  const int rows = 5, cols = 7;
  const Cloth cloth = build_cloth(testing::small_cloth(rows, cols));
  std::map<SpringFamily, int> count;
  for (Eigen::Index e = 0; e < cloth.springs.size(); ++e) {
    const SpringFamily f = cloth.springs.family[e];
    ++count[f];
    const double expected = f == SpringFamily::structural ? 0.02
                            : f == SpringFamily::shear    ? 0.02 * std::sqrt(2.0)
                                                          : 0.04;
    EXPECT_NEAR(cloth.springs.rest[e], expected, 1e-15);
    const double k = f == SpringFamily::structural ? 20.0 : f == SpringFamily::shear ? 10.0 : 2.0;
    EXPECT_EQ(cloth.springs.stiffness[e], k);
  }
  EXPECT_EQ(count[SpringFamily::structural], rows * (cols - 1) + (rows - 1) * cols);
  EXPECT_EQ(count[SpringFamily::shear], 2 * (rows - 1) * (cols - 1));
  EXPECT_EQ(count[SpringFamily::bending], rows * (cols - 2) + (rows - 2) * cols);
}

TEST(Cloth, ZeroStiffnessFamilyHasNoSprings) {
  ClothParams p = testing::small_cloth(4, 4);
  p.k_shear = 0.0;
  p.k_bending = 0.0;
  const Cloth cloth = build_cloth(p);
  EXPECT_EQ(cloth.springs.size(), 2 * 4 * 3);
}

}  // namespace
}  // namespace drape

namespace drape {
namespace {

TEST(Cloth, SpringsComeInClassesOfDisjointPairs) {
  // The per-spring Jacobian loops rely on it: within a class no particle appears twice.
  const Cloth cloth = build_cloth(testing::small_cloth(7, 9));
  std::vector<int> last_class(cloth.size(), -1);
  int classes = 0;
  std::vector<bool> used(cloth.size(), false);
  for (Eigen::Index e = 0; e < cloth.springs.size(); ++e) {
    const int i = cloth.springs.first[e], j = cloth.springs.second[e];
    if (used[i] || used[j]) {  // a new class starts here
      std::fill(used.begin(), used.end(), false);
      ++classes;
    }
    used[i] = used[j] = true;
  }
  EXPECT_EQ(classes + 1, 12) << "two classes per offset, six offsets";
}

}  // namespace
}  // namespace drape
