// drapelab_bench: one 1/30 s frame of xpbd (20 substeps of one Gauss-Seidel sweep, the setting
// that keeps up with the Kinect at 64 x 64; the default is 80) on the n x n cloth of draped_cloth.hpp with its top row pinned, free (no object) and
// draped on the dress form with the smooth contact model, at 32 x 32, 64 x 64 and 128 x 128.
// See docs/integrators/xpbd.md.
#include <benchmark/benchmark.h>

#include "experiments/benchmarks/draped_cloth.hpp"
#include "integrators/registry/registry.hpp"

namespace drape {
namespace {

void xpbd_frame(benchmark::State& state, bool draped) {
  Eigen::VectorXd y;
  const int n = static_cast<int>(state.range(0));
  auto system = bench::draped_cloth(n, y, draped, CollisionModel::smooth);
  for (int col = 0; col < n; ++col) system->constraints().fix_at(col, y.segment<3>(3 * col));
  IntegratorOptions options;
  options.name = "xpbd";
  options.dt = 1.0 / 30.0;
  options.settings = {{"substeps", 20}};
  auto method = make_integrator(options, *system);
  method->reset(0.0, y);
  for (auto _ : state) method->step(1e9);
  const IntegratorCounters& counters = method->counters();
  state.counters["sweeps_per_frame"] =
      static_cast<double>(counters.newton_iters) / static_cast<double>(counters.steps);
  // Wall time per particle and sweep: the cost of one constraint projection pass.
  state.counters["ns_per_particle_sweep"] = benchmark::Counter(
      static_cast<double>(counters.newton_iters) * n * n * 1e-9,
      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

const bool registered = [] {
  for (const bool draped : {false, true})
    benchmark::RegisterBenchmark(draped ? "BM_XpbdFrame/draped-smooth" : "BM_XpbdFrame/free",
                                 [draped](benchmark::State& state) { xpbd_frame(state, draped); })
        ->RangeMultiplier(2)
        ->Range(32, 128)
        ->Unit(benchmark::kMillisecond);
  return true;
}();

}  // namespace
}  // namespace drape
