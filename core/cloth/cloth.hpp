#pragma once
// The paper's cloth model (section 2.1, Figure 1): particles on a grid joined by springs to
// their nearest (structural), next-nearest (shear) and optionally second (bending) neighbours.
#include <Eigen/Core>
#include <vector>

#include "core/cloth/spring_list.hpp"
#include "core/cloth/spring_stencil.hpp"
#include "core/state/state.hpp"

namespace drape {

/// A cloth particle named by its grid coordinates.
struct GridPoint {
  int row = 0;
  int col = 0;
};

/// Grid geometry, mass and spring constants of a cloth (docs/model.md section 2).
struct ClothParams {
  int rows = 0;
  int cols = 0;
  double spacing = 0.0;
  Vec3 origin = Vec3::Zero();
  Vec3 col_dir = Vec3::UnitX();
  Vec3 row_dir = -Vec3::UnitY();
  double particle_mass = 0.0;
  double k_structural = 0.0;
  double k_shear = 0.0;
  double k_bending = 0.0;
  double damping_spring = 0.0;
  double damping_air = 0.0;
};

/// A built cloth: parameters, initial grid positions and springs.
struct Cloth {
  ClothParams params;
  Eigen::VectorXd rest_positions;  ///< 3N, the initial grid
  /// The springs: one stencil per offset of a family (spring_stencil.hpp), the force loop's.
  std::vector<SpringStencil> stencils;
  /// The same springs listed, list_springs(stencils, rows, cols), for the per-spring loops.
  SpringList springs;

  int size() const { return params.rows * params.cols; }
  int index(int row, int col) const { return row * params.cols + col; }
  int row_of(int i) const { return i / params.cols; }
  int col_of(int i) const { return i % params.cols; }
};

/// Builds the grid and its springs; a family with stiffness 0 has no springs.
Cloth build_cloth(const ClothParams& params);

}  // namespace drape
