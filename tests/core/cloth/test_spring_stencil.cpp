// A stencil's grid quantities (spring_stencil.hpp) against the pairs they describe, found by
// trying every particle of the grid.
#include <gtest/gtest.h>

#include "core/cloth/spring_stencil.hpp"

namespace drape {
namespace {

// Every offset of docs/model.md section 2, a reversed one, on grids thinner than some offsets.
TEST(SpringStencil, RowsColumnsAndOffsetAreThoseOfThePairsOnTheGrid) {
  const int offsets[][2] = {{0, 1}, {1, 0}, {1, 1}, {1, -1}, {0, 2}, {2, 0}, {0, -1}};
  const int grids[][2] = {{5, 7}, {1, 1}, {1, 6}, {6, 1}, {2, 2}, {3, 2}};
  for (const auto& [dr, dc] : offsets)
    for (const auto& [rows, cols] : grids) {
      const SpringStencil s{dr, dc};
      EXPECT_EQ(s.along_row(), dr == 0);
      long pairs = 0;
      for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c) {
          const bool on_grid = r + dr < rows && c + dc >= 0 && c + dc < cols;
          const bool listed = r < s.end_row(rows) && c >= s.first_col() && c < s.end_col(cols);
          EXPECT_EQ(listed, on_grid) << dr << ", " << dc << " at " << r << ", " << c;
          if (!on_grid) continue;
          ++pairs;
          EXPECT_EQ((r + dr) * cols + c + dc - (r * cols + c), s.offset(cols));
        }
      const long rows_with_springs = s.end_row(rows) > 0 ? s.end_row(rows) : 0;
      EXPECT_EQ(pairs, s.count(cols) > 0 ? rows_with_springs * s.count(cols) : 0)
          << dr << ", " << dc << " on " << rows << " x " << cols;
    }
}

}  // namespace
}  // namespace drape
