#include "core/cloth/cloth.hpp"

#include <cstdlib>

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

// Lists the stencils' springs in colour classes, each a matching of the grid: no two springs of
// a class share a particle. Loops that scatter per spring (Jacobian products, assembly) then have
// no read-after-write chains between neighbouring springs, and each class sweeps the grid in
// memory order.
SpringSet list_springs(const std::vector<SpringStencil>& stencils, int rows, int cols) {
  std::vector<int> first, second;
  std::vector<const SpringStencil*> of;
  for (const SpringStencil& s : stencils) {
    // Springs of one offset sharing a particle start one stride apart along its major axis;
    // alternating blocks of `stride` starts never touch.
    const int stride = s.dr != 0 ? s.dr : std::abs(s.dc);
    for (int colour = 0; colour < 2; ++colour)
      for (int r = 0; r + s.dr < rows; ++r)
        for (int c = s.first_col(); c < s.end_col(cols); ++c) {
          const int major = s.dr != 0 ? r : c;
          if ((major / stride) % 2 != colour) continue;
          first.push_back(r * cols + c);
          second.push_back((r + s.dr) * cols + c + s.dc);
          of.push_back(&s);
        }
  }
  const auto n = static_cast<Eigen::Index>(first.size());
  SpringSet set;
  set.first = Eigen::Map<Eigen::ArrayXi>(first.data(), n);
  set.second = Eigen::Map<Eigen::ArrayXi>(second.data(), n);
  set.rest.resize(n);
  set.stiffness.resize(n);
  set.family.reserve(of.size());
  for (Eigen::Index e = 0; e < n; ++e) {
    const SpringStencil& s = *of[static_cast<std::size_t>(e)];
    set.rest[e] = s.rest;
    set.stiffness[e] = s.stiffness;
    set.family.push_back(s.family);
  }
  return set;
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
