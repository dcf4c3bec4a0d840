// Grid geometry and spring families of docs/model.md section 2.
#include <gtest/gtest.h>

#include <cmath>
#include <iterator>

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

TEST(Cloth, StencilsAreTheFamiliesOffsetsWithTheirConstants) {
  const Cloth cloth = build_cloth(testing::small_cloth(5, 7));
  const struct {
    int dr, dc;
    SpringFamily family;
    double stiffness, rest;
  } expected[] = {{0, 1, SpringFamily::structural, 20.0, 0.02},
                  {1, 0, SpringFamily::structural, 20.0, 0.02},
                  {1, 1, SpringFamily::shear, 10.0, 0.02 * std::sqrt(2.0)},
                  {1, -1, SpringFamily::shear, 10.0, 0.02 * std::sqrt(2.0)},
                  {0, 2, SpringFamily::bending, 2.0, 0.04},
                  {2, 0, SpringFamily::bending, 2.0, 0.04}};
  ASSERT_EQ(cloth.stencils.size(), std::size(expected));
  for (std::size_t k = 0; k < std::size(expected); ++k) {
    const SpringStencil& s = cloth.stencils[k];
    EXPECT_EQ(s.dr, expected[k].dr);
    EXPECT_EQ(s.dc, expected[k].dc);
    EXPECT_EQ(s.family, expected[k].family);
    EXPECT_EQ(s.stiffness, expected[k].stiffness);
    EXPECT_NEAR(s.rest, expected[k].rest, 1e-15);
  }
}

TEST(Cloth, ZeroStiffnessFamilyHasNoStencils) {
  ClothParams p = testing::small_cloth(4, 4);
  p.k_shear = 0.0;
  p.k_bending = 0.0;
  const Cloth cloth = build_cloth(p);
  ASSERT_EQ(cloth.stencils.size(), 2u);
  EXPECT_EQ(cloth.stencils[0].family, SpringFamily::structural);
  EXPECT_EQ(cloth.stencils[1].family, SpringFamily::structural);
  EXPECT_EQ(cloth.springs.size(), 2 * 4 * 3);
}

}  // namespace
}  // namespace drape
