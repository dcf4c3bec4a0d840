#include "core/cloth/spring_list.hpp"

#include <cstdlib>

namespace drape {

SpringList list_springs(const std::vector<SpringStencil>& stencils, int rows, int cols) {
  std::vector<int> first, second;
  std::vector<double> rest, stiffness;
  for (const SpringStencil& s : stencils) {
    const int stride = s.along_row() ? std::abs(s.dc) : s.dr;
    for (int colour = 0; colour < 2; ++colour)
      for (int r = 0; r < s.end_row(rows); ++r)
        for (int c = s.first_col(); c < s.end_col(cols); ++c) {
          if (((s.along_row() ? c : r) / stride) % 2 != colour) continue;
          first.push_back(r * cols + c);
          second.push_back(first.back() + static_cast<int>(s.offset(cols)));
          rest.push_back(s.rest);
          stiffness.push_back(s.stiffness);
        }
  }
  const auto n = static_cast<Eigen::Index>(first.size());
  SpringList list;
  list.first = Eigen::Map<Eigen::ArrayXi>(first.data(), n);
  list.second = Eigen::Map<Eigen::ArrayXi>(second.data(), n);
  list.rest = Eigen::Map<Eigen::ArrayXd>(rest.data(), n);
  list.stiffness = Eigen::Map<Eigen::ArrayXd>(stiffness.data(), n);
  return list;
}

}  // namespace drape
