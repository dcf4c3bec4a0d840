#pragma once
// The explicit steps' update of the state, element by element, on the hot loops' threads
// (core/parallel): each element's value is the same whatever the split.
#include "core/model/cloth_system.hpp"
#include "core/state/state.hpp"
#include "core/parallel/parallel_for.hpp"

namespace drape {

/// v += h_kick a, then x += h_drift v (the new v), particle by particle.
inline void kick_drift(VecRef x, VecRef v, ConstVecRef a, double h_kick, double h_drift) {
  parallel_for(x.size() / 3, threaded_particles_from, [&](std::ptrdiff_t begin, std::ptrdiff_t end) {
    for (Eigen::Index k = 3 * begin; k < 3 * end; ++k) {
      v[k] += h_kick * a[k];
      x[k] += h_drift * v[k];
    }
  });
}

/// v += h_kick a, particle by particle.
inline void kick(VecRef v, ConstVecRef a, double h_kick) {
  parallel_for(v.size() / 3, threaded_particles_from, [&](std::ptrdiff_t begin, std::ptrdiff_t end) {
    v.segment(3 * begin, 3 * (end - begin)) += h_kick * a.segment(3 * begin, 3 * (end - begin));
  });
}

/// v += h_kick a, then the Coulomb bound on each contact's tangential change of v
/// (docs/model.md section 4.12; nothing without friction).
inline void kick_friction(const ClothSystem& system, ConstVecRef x, VecRef v, ConstVecRef a,
                          double h_kick) {
  kick(v, a, h_kick);
  system.apply_velocity_friction(x, v, h_kick);
}

/// kick_friction, then x += h_drift v; without friction kick_drift's one fused pass.
inline void kick_friction_drift(const ClothSystem& system, VecRef x, VecRef v, ConstVecRef a,
                                double h_kick, double h_drift) {
  if (system.friction().coefficient() == 0.0) return kick_drift(x, v, a, h_kick, h_drift);
  kick_friction(system, x, v, a, h_kick);
  x += h_drift * v;
}

}  // namespace drape
