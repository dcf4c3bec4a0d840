// The flat listing of spring_list.hpp against the stencils it lists: the same springs, stencil
// by stencil, in two classes of disjoint pairs each sweeping the grid in memory order.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>
#include <utility>
#include <vector>

#include "core/cloth/cloth.hpp"
#include "tests/support/test_support.hpp"

namespace drape {
namespace {

// A 7 x 9 cloth of every family (odd sizes: the two classes of an offset differ in size).
TEST(SpringList, ListsEachStencilsPairsInOneBlockWithItsConstants) {
  const Cloth cloth = build_cloth(testing::small_cloth(7, 9));
  const int rows = 7, cols = 9;
  ASSERT_EQ(cloth.stencils.size(), 6u);
  const SpringList list = list_springs(cloth.stencils, rows, cols);
  Eigen::Index e = 0;
  for (const SpringStencil& s : cloth.stencils) {
    std::set<std::pair<int, int>> expected, listed;
    for (int r = 0; r < rows; ++r)
      for (int c = 0; c < cols; ++c)
        if (r + s.dr < rows && c + s.dc >= 0 && c + s.dc < cols)
          expected.insert({r * cols + c, (r + s.dr) * cols + c + s.dc});
    for (std::size_t k = 0; k < expected.size(); ++k, ++e) {
      ASSERT_LT(e, list.size());
      listed.insert({list.first[e], list.second[e]});
      EXPECT_EQ(list.rest[e], s.rest);
      EXPECT_EQ(list.stiffness[e], s.stiffness);
    }
    EXPECT_EQ(listed, expected) << "stencil (" << s.dr << ", " << s.dc << ")";
  }
  EXPECT_EQ(e, list.size());
  EXPECT_TRUE((list.first == cloth.springs.first).all());
  EXPECT_TRUE((list.second == cloth.springs.second).all());
}

TEST(SpringList, SpringCountsPerFamily) {
  const int rows = 5, cols = 7;
  const Cloth cloth = build_cloth(testing::small_cloth(rows, cols));
  std::map<SpringFamily, long> count;
  for (const SpringStencil& s : cloth.stencils) count[s.family] += s.end_row(rows) * s.count(cols);
  EXPECT_EQ(count[SpringFamily::structural], rows * (cols - 1) + (rows - 1) * cols);
  EXPECT_EQ(count[SpringFamily::shear], 2 * (rows - 1) * (cols - 1));
  EXPECT_EQ(count[SpringFamily::bending], rows * (cols - 2) + (rows - 2) * cols);
  EXPECT_EQ(cloth.springs.size(), count[SpringFamily::structural] + count[SpringFamily::shear] +
                                      count[SpringFamily::bending]);
}

// The per-spring Jacobian loops rely on it: within a class no particle appears twice. A class
// ends where a spring shares a particle with it or starts before its last spring; 12 runs so cut
// are the two classes of each of the six offsets.
TEST(SpringList, SpringsComeInClassesOfDisjointPairsInMemoryOrder) {
  const Cloth cloth = build_cloth(testing::small_cloth(7, 9));
  const SpringList& list = cloth.springs;
  std::vector<bool> used(cloth.size(), false);
  int classes = 1;
  for (Eigen::Index e = 0; e < list.size(); ++e) {
    const int i = list.first[e], j = list.second[e];
    if (used[i] || used[j] || (e > 0 && i < list.first[e - 1])) {
      std::fill(used.begin(), used.end(), false);
      ++classes;
    }
    used[i] = used[j] = true;
  }
  EXPECT_EQ(classes, 12);
}

}  // namespace
}  // namespace drape
