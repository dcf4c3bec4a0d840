#pragma once
// The paper's cloth model (section 2.1, Figure 1): particles on a grid joined by springs to
// their nearest (structural), next-nearest (shear) and optionally second (bending) neighbours.
#include <Eigen/Core>
#include <algorithm>
#include <cstdint>
#include <vector>

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

/// The spring families of docs/model.md section 2.
enum class SpringFamily : std::uint8_t { structural, shear, bending };

/// One spring family's offset as a stencil on the grid: spring (r, c) joins particle (r, c) to
/// (r + dr, c + dc) wherever both are on the grid. Its springs share stiffness and rest length
/// (the offset's length on the initial grid), and the springs of one grid row form a contiguous
/// run in both particles, which the force loop streams through.
struct SpringStencil {
  int dr = 0;
  int dc = 0;
  double stiffness = 0.0;
  double rest = 0.0;
  SpringFamily family = SpringFamily::structural;

  int first_col() const { return std::max(0, -dc); }
  int end_col(int cols) const { return cols - std::max(0, dc); }
};

/// All springs as flat arrays, one entry per spring, for the Jacobian and energy loops.
struct SpringSet {
  Eigen::ArrayXi first;       ///< particle i
  Eigen::ArrayXi second;      ///< particle j
  Eigen::ArrayXd rest;        ///< rest length L0
  Eigen::ArrayXd stiffness;   ///< k
  std::vector<SpringFamily> family;

  Eigen::Index size() const { return first.size(); }
};

/// A built cloth: parameters, initial grid positions and springs.
struct Cloth {
  ClothParams params;
  Eigen::VectorXd rest_positions;  ///< 3N, the initial grid
  std::vector<SpringStencil> stencils;  ///< one per offset of a family with stiffness > 0
  SpringSet springs;                    ///< the same springs, listed

  int size() const { return params.rows * params.cols; }
  int index(int row, int col) const { return row * params.cols + col; }
  int row_of(int i) const { return i / params.cols; }
  int col_of(int i) const { return i % params.cols; }
};

/// Builds the grid and its springs; a family with stiffness 0 has no springs.
Cloth build_cloth(const ClothParams& params);

}  // namespace drape
