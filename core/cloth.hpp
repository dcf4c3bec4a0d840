#pragma once
// The paper's cloth model (section 2.1, Figure 1): particles on a grid joined by springs to
// their nearest (structural), next-nearest (shear) and optionally second (bending) neighbours.
#include <Eigen/Core>
#include <cstdint>

#include "core/state.hpp"

namespace drape {

/// Grid geometry, mass and spring constants of a cloth (SPEC 2).
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

/// The spring families of SPEC 2.
enum class SpringFamily : std::uint8_t { structural, shear, bending };

/// All springs as flat arrays that the force loops stream through.
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
  SpringSet springs;

  int size() const { return params.rows * params.cols; }
  int index(int row, int col) const { return row * params.cols + col; }
  int row_of(int i) const { return i / params.cols; }
  int col_of(int i) const { return i % params.cols; }
};

/// Builds the grid and its springs; a family with stiffness 0 has no springs.
Cloth build_cloth(const ClothParams& params);

}  // namespace drape
