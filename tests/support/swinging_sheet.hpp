#pragma once
// The swinging sheet (docs/integrators/line-search-newton.md): 12 x 12, horizontal, pinned at
// the two corners of its first row, no object, with the drape scene's spacing, mass, stiffness and damping
// (experiments/scenes/drape_dress_form.json) times `stiffness_factor`. Released at rest it falls
// and swings: at 1/30 s its implicit stages are the hard ones of
// docs/integrators/line-search-newton.md. `damping_spring` replaces the drape scene's 0.01 (0: E
// is then one function of the state, not frozen at an iterate's spring directions).
#include <memory>

#include "core/model/cloth_system.hpp"
#include "tests/support/test_support.hpp"

namespace drape::testing {

inline std::unique_ptr<ClothSystem> swinging_sheet(double stiffness_factor, int size = 12,
                                                   double damping_spring = 0.01) {
  ClothParams p = small_cloth(size, size);
  p.origin = Vec3(-0.11, 1.3, 0.0);
  p.col_dir = Vec3(1.0, 0.0, 0.0);
  p.row_dir = Vec3(0.0, 0.0, 1.0);
  p.particle_mass = 6e-5;
  p.k_structural = p.k_shear = 50.0 * stiffness_factor;
  p.k_bending = 0.0;
  p.damping_spring = damping_spring;
  p.damping_air = 1e-4;
  auto s = std::make_unique<ClothSystem>(build_cloth(p), nullptr, ForceParams{});
  const Eigen::VectorXd& rest = s->cloth().rest_positions;
  s->constraints().fix_at(0, rest.segment<3>(0));
  s->constraints().fix_at(size - 1, rest.segment<3>(3 * (size - 1)));
  return s;
}

}  // namespace drape::testing
