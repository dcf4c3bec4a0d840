// drapelab_bench: one 1/30 s frame of projective-dynamics at 10 and 100 iterations, at 32 x 32,
// 64 x 64 and 128 x 128, on a free sheet (flat, two corners pinned: the setup of the peer
// comparison with seiing/FastMassSpring) and on the draped cloth (top row pinned, smooth
// collision model). The first step, with the factorisation, runs before the timed loop.
// See docs/integrators/projective-dynamics.md.
#include <benchmark/benchmark.h>

#include "experiments/benchmarks/draped_cloth.hpp"
#include "integrators/registry/registry.hpp"

namespace drape {
namespace {

// An n x n horizontal sheet with draped_cloth's spacing, mass, springs and damping, its two
// corners of the first row pinned, at rest.
std::unique_ptr<ClothSystem> free_sheet(int n, Eigen::VectorXd& y) {
  Eigen::VectorXd unused;
  ClothParams p = bench::draped_cloth(n, unused, false)->cloth().params;
  p.col_dir = Vec3::UnitX();
  p.row_dir = Vec3::UnitZ();
  auto system = std::make_unique<ClothSystem>(build_cloth(p), nullptr, ForceParams{});
  for (const int corner : {0, n - 1})
    system->constraints().fix_at(corner, system->cloth().rest_positions.segment<3>(3 * corner));
  y = system->initial_state(0.0);
  return system;
}

std::unique_ptr<ClothSystem> draped(int n, Eigen::VectorXd& y) {
  auto system = bench::draped_cloth(n, y, true, CollisionModel::smooth);
  for (int col = 0; col < n; ++col) system->constraints().fix_at(col, y.segment<3>(3 * col));
  return system;
}

void run_frames(benchmark::State& state, bool on_dress_form, bool chebyshev) {
  Eigen::VectorXd y;
  const int n = static_cast<int>(state.range(0));
  auto system = on_dress_form ? draped(n, y) : free_sheet(n, y);
  IntegratorOptions options;
  options.name = "projective-dynamics";
  options.dt = 1.0 / 30.0;
  options.settings = {{"iterations", state.range(1)}, {"chebyshev", chebyshev}};
  auto method = make_integrator(options, *system);
  method->reset(0.0, y);
  method->step(1e9);
  const long setups_before = method->counters().jacobian_setups;
  for (auto _ : state) method->step(1e9);
  state.counters["refactors_per_frame"] = benchmark::Counter(
      static_cast<double>(method->counters().jacobian_setups - setups_before),
      benchmark::Counter::kAvgIterations);
  state.counters["us_per_iteration"] = benchmark::Counter(
      static_cast<double>(state.range(1)) * 1e-6,
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

const bool registered = [] {
  for (const bool on_dress_form : {false, true})
    for (const bool chebyshev : {false, true})
      benchmark::RegisterBenchmark(
          (std::string("BM_ProjectiveDynamicsFrame/") + (on_dress_form ? "draped" : "free") +
           (chebyshev ? "/chebyshev" : ""))
              .c_str(),
          [on_dress_form, chebyshev](benchmark::State& state) {
            run_frames(state, on_dress_form, chebyshev);
          })
          ->ArgsProduct({{32, 64, 128}, {10, 100}})
          ->ArgNames({"n", "iterations"})
          ->Unit(benchmark::kMillisecond);
  return true;
}();

}  // namespace
}  // namespace drape
