#pragma once
// The scenes of the implicit-step benchmarks: the swinging sheet (free of any object) and the
// draped cloth with the smooth contact model, at any resolution.
#include <memory>

#include "experiments/benchmarks/draped_cloth.hpp"

namespace drape::bench {

/// An n x n sheet of 0.5 m side with particles of `particle_mass` (k = 50 N/m, draped_cloth's
/// cloth), horizontal, pinned at the two corners of its first row, no object: released at rest
/// it falls and swings (the sheet of docs/integrators/line-search-newton.md at the
/// benchmarks' resolutions).
inline std::unique_ptr<ClothSystem> sheet_of(int n, double particle_mass, Eigen::VectorXd& y) {
  ClothParams p;
  p.rows = p.cols = n;
  p.spacing = 0.5 / n;
  p.particle_mass = particle_mass;
  p.k_structural = p.k_shear = 50.0;
  p.damping_spring = 0.01;
  p.damping_air = 1e-4;
  p.origin = Vec3(-0.25, 1.3, 0.0);
  p.col_dir = Vec3(1.0, 0.0, 0.0);
  p.row_dir = Vec3(0.0, 0.0, 1.0);
  auto system = std::make_unique<ClothSystem>(build_cloth(p), nullptr, ForceParams{});
  y = system->initial_state(0.0);
  for (const int corner : {0, n - 1})
    system->constraints().fix_at(corner, y.segment<3>(3 * corner));
  return system;
}

/// The sheet of 0.2 kg: refined, its particles get lighter and gamma^2 k / m, the stiffness S
/// holds against the mass, grows 4x per refinement (docs/performance/implicit-step.md's scaling benchmark).
inline std::unique_ptr<ClothSystem> swinging_sheet(int n, Eigen::VectorXd& y) {
  return sheet_of(n, 0.2 / (n * n), y);
}

/// The sheet with the particles of the 64 x 64 sheet at every size (0.8 kg at 128 x 128):
/// gamma^2 k / m is the same at every n, so the solver's scaling shows without the growth of
/// the system's stiffness (docs/journal/2026-11-27-growth-is-the-cloth.md).
inline std::unique_ptr<ClothSystem> sheet_of_equal_particles(int n, Eigen::VectorXd& y) {
  return sheet_of(n, 0.2 / (64 * 64), y);
}

/// draped_cloth with the smooth contact model, top row pinned.
inline std::unique_ptr<ClothSystem> smooth_drape(int n, Eigen::VectorXd& y) {
  auto system = draped_cloth(n, y, true, CollisionModel::smooth);
  for (int col = 0; col < n; ++col) system->constraints().fix_at(col, y.segment<3>(3 * col));
  return system;
}

}  // namespace drape::bench
