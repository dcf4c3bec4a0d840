#include "core/cloth.hpp"

#include <vector>

namespace drape {

namespace {

struct SpringList {
  std::vector<int> first, second;
  std::vector<double> stiffness;
  std::vector<SpringFamily> family;

  void add(int i, int j, double k, SpringFamily f) {
    first.push_back(i);
    second.push_back(j);
    stiffness.push_back(k);
    family.push_back(f);
  }
};

}  // namespace

Cloth build_cloth(const ClothParams& params) {
  Cloth cloth;
  cloth.params = params;
  const int rows = params.rows, cols = params.cols;
  cloth.rest_positions.resize(3 * rows * cols);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c)
      particle(cloth.rest_positions, cloth.index(r, c)) =
          params.origin + c * params.spacing * params.col_dir + r * params.spacing * params.row_dir;

  // Springs are emitted row by row so that both ends of most springs are close in memory.
  SpringList list;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      const int i = cloth.index(r, c);
      if (params.k_structural > 0) {
        if (c + 1 < cols) list.add(i, i + 1, params.k_structural, SpringFamily::structural);
        if (r + 1 < rows) list.add(i, i + cols, params.k_structural, SpringFamily::structural);
      }
      if (params.k_shear > 0 && r + 1 < rows && c + 1 < cols) {
        list.add(i, i + cols + 1, params.k_shear, SpringFamily::shear);
        list.add(i + 1, i + cols, params.k_shear, SpringFamily::shear);
      }
      if (params.k_bending > 0) {
        if (c + 2 < cols) list.add(i, i + 2, params.k_bending, SpringFamily::bending);
        if (r + 2 < rows) list.add(i, i + 2 * cols, params.k_bending, SpringFamily::bending);
      }
    }
  }
  const auto n = static_cast<Eigen::Index>(list.first.size());
  SpringSet& s = cloth.springs;
  s.first = Eigen::Map<Eigen::ArrayXi>(list.first.data(), n);
  s.second = Eigen::Map<Eigen::ArrayXi>(list.second.data(), n);
  s.stiffness = Eigen::Map<Eigen::ArrayXd>(list.stiffness.data(), n);
  s.family = std::move(list.family);
  s.rest.resize(n);
  for (Eigen::Index e = 0; e < n; ++e)
    s.rest[e] = (particle(cloth.rest_positions, s.second[e]) -
                 particle(cloth.rest_positions, s.first[e])).norm();
  return cloth;
}

}  // namespace drape
