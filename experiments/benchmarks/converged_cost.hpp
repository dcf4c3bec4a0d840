#pragma once
// The frames of the converged-cost comparison (docs/performance/converged-cost.md), shared by
// bench_converged_cost.cpp, which times them, and tests/validation/test_converged_cost.cpp,
// which checks the iteration counts its table states: the fourth 1/30 s frame of the swinging
// sheet and of the smooth drape (bench_scenes.hpp), converged backward Euler's step on it (the
// line-search Newton at a tight tolerance), and the methods that approach it with a count.
#include <algorithm>
#include <memory>
#include <string>

#include "experiments/benchmarks/bench_scenes.hpp"
#include "integrators/registry/registry.hpp"
#include "tests/support/backward_euler_reference.hpp"

namespace drape::bench {

inline constexpr double cost_frame = 1.0 / 30.0;

enum class CostScene { sheet, drape };

inline const char* scene_name(CostScene scene) {
  return scene == CostScene::sheet ? "sheet" : "drape";
}

/// The reference: converged backward Euler far below the distances compared (weighted update
/// 0.1 / 1e10 of |y|: about 1e-11 m), solved with sparse LDLT, not the compared CG.
inline IntegratorOptions reference_newton() {
  return testing::converged_backward_euler(cost_frame, 1e-10, 1e-12, "sparse-direct");
}

/// One frame of `options` from y; the end state.
inline Eigen::VectorXd one_frame(ClothSystem& system, const Eigen::VectorXd& y,
                                 const IntegratorOptions& options) {
  auto method = make_integrator(options, system);
  method->reset(0.0, y);
  method->step(cost_frame);
  return method->state();
}

/// Largest particle distance (m) between the positions (first half) of two states.
inline double position_distance(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  double largest = 0.0;
  for (Eigen::Index i = 0; i < a.size() / 6; ++i)
    largest = std::max(largest, (a.segment<3>(3 * i) - b.segment<3>(3 * i)).norm());
  return largest;
}

/// The compared step: the state y after three reference frames from the scene's start (so that
/// the cloth moves: the swinging sheet falls and swings, the drape slides into contact), and
/// the reference frame from y.
struct CostFrame {
  std::unique_ptr<ClothSystem> system;
  Eigen::VectorXd y, reference;
};

/// The swinging sheet (bench_scenes.hpp, 0.2 kg, two corners pinned) or the smooth drape
/// (draped_cloth round the dress form, smooth contact, top row pinned) at n x n.
inline CostFrame cost_frame_of(CostScene scene, int n) {
  CostFrame f;
  f.system = scene == CostScene::sheet ? swinging_sheet(n, f.y) : smooth_drape(n, f.y);
  for (int k = 0; k < 3; ++k) f.y = one_frame(*f.system, f.y, reference_newton());
  f.reference = one_frame(*f.system, f.y, reference_newton());
  return f;
}

/// A method whose distance to the reference is set by its `iterations` key.
struct IteratedMethod {
  const char* label;
  const char* name;
  bool chebyshev;
  double rho;  ///< Chebyshev's spectral radius estimate (used with chebyshev only)
};

/// PD and VBD plain and Chebyshev-accelerated (Wang 2015). PD's rho near its plain contraction
/// (1 - 1.5e-4 an iteration on the 12 x 12 sheet, docs/integrators/projective-dynamics.md);
/// VBD's default 0.95 and a larger one. VBD starts at its default, `velocity`.
inline const IteratedMethod iterated_methods[] = {
    {"pd", "projective-dynamics", false, 0.9},
    {"pd-chebyshev-0.999", "projective-dynamics", true, 0.999},
    {"pd-chebyshev-0.9999", "projective-dynamics", true, 0.9999},
    {"vbd", "vbd", false, 0.95},
    {"vbd-chebyshev-0.95", "vbd", true, 0.95},
    {"vbd-chebyshev-0.99", "vbd", true, 0.99},
};

inline IntegratorOptions iterated_options(const IteratedMethod& m, long iterations) {
  IntegratorOptions o;
  o.name = m.name;
  o.dt = cost_frame;
  o.settings = {{"iterations", iterations}, {"chebyshev", m.chebyshev}, {"rho", m.rho}};
  return o;
}

}  // namespace drape::bench
