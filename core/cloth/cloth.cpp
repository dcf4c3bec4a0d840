#include "core/cloth/cloth.hpp"

namespace drape {

namespace {

// The offsets of docs/model.md section 2's families; a family with stiffness 0 has no stencils.
std::vector<SpringStencil> spring_stencils(const ClothParams& params) {
  const SpringStencil offsets[] = {
      {0, 1, params.k_structural, 0.0, SpringFamily::structural},
      {1, 0, params.k_structural, 0.0, SpringFamily::structural},
      {1, 1, params.k_shear, 0.0, SpringFamily::shear},
      {1, -1, params.k_shear, 0.0, SpringFamily::shear},
      {0, 2, params.k_bending, 0.0, SpringFamily::bending},
      {2, 0, params.k_bending, 0.0, SpringFamily::bending},
  };
  std::vector<SpringStencil> stencils;
  for (SpringStencil s : offsets) {
    if (s.stiffness <= 0.0) continue;
    // One length per offset: every pair of the offset is this far apart on the initial grid.
    s.rest = (s.dc * params.spacing * params.col_dir + s.dr * params.spacing * params.row_dir).norm();
    stencils.push_back(s);
  }
  return stencils;
}

}  // namespace

Cloth build_cloth(const ClothParams& params) {
  Cloth cloth;
  cloth.params = params;
  const int rows = params.rows, cols = params.cols;
  cloth.rest_positions.resize(3 * static_cast<Eigen::Index>(rows) * cols);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c)
      particle(cloth.rest_positions, cloth.index(r, c)) =
          params.origin + c * params.spacing * params.col_dir + r * params.spacing * params.row_dir;
  cloth.stencils = spring_stencils(params);
  cloth.springs = list_springs(cloth.stencils, rows, cols);
  return cloth;
}

}  // namespace drape
