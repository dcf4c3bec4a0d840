// drapelab_bench: one 1/30 s frame step of bdf2 beside implicit-euler's, both one linearised
// solve a step on their default pcg-multigrid (linear tolerance 1e-3), at 32 x 32, 64 x 64 and
// 128 x 128, on the swinging sheet and on the dress form with the smooth contact model
// (bench_scenes.hpp). See docs/integrators/bdf2.md.
//
// Three steps run before timing (the first holds the one-time setup: patterns, multigrid levels;
// the second is bdf2's implicit Euler start), then 60 steps, 2 s of motion, are timed: the CG
// iterations follow the motion.
#include <benchmark/benchmark.h>

#include "experiments/benchmarks/bench_scenes.hpp"
#include "integrators/registry/registry.hpp"

namespace drape {
namespace {

constexpr int warm_up_steps = 3, timed_steps = 60;

using Scene = std::unique_ptr<ClothSystem> (*)(int, Eigen::VectorXd&);

void run_frames(benchmark::State& state, Scene scene, const std::string& integrator) {
  Eigen::VectorXd y;
  auto system = scene(static_cast<int>(state.range(0)), y);
  IntegratorOptions options;
  options.name = integrator;
  options.dt = 1.0 / 30.0;
  auto method = make_integrator(options, *system);
  method->reset(0.0, y);
  for (int k = 0; k < warm_up_steps; ++k) method->step(1e9);
  const IntegratorCounters before = method->counters();
  for (auto _ : state) method->step(1e9);
  const IntegratorCounters& after = method->counters();
  state.counters["linear_per_step"] =
      benchmark::Counter(static_cast<double>(after.linear_iters - before.linear_iters),
                         benchmark::Counter::kAvgIterations);
  state.counters["cg_failures"] = static_cast<double>(after.convergence_failures);
}

const bool registered = [] {
  const std::pair<const char*, Scene> scenes[] = {{"sheet", bench::swinging_sheet},
                                                  {"dress-form-smooth", bench::smooth_drape}};
  for (const auto& [label, scene] : scenes)
    for (const char* integrator : {"implicit-euler", "bdf2"})
      benchmark::RegisterBenchmark(
          (std::string("BM_Bdf2Frame/") + label + "/" + integrator).c_str(),
          [scene = scene, integrator](benchmark::State& state) {
            run_frames(state, scene, integrator);
          })
          ->Arg(32)
          ->Arg(64)
          ->Arg(128)
          ->Iterations(timed_steps)
          ->Unit(benchmark::kMillisecond);
  return true;
}();

}  // namespace
}  // namespace drape
