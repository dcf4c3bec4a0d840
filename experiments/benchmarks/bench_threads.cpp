// The hot loops on 1 and 2 threads (core/parallel): the force evaluation of the wrapped cloth,
// a leap-frog step of the settled drape, and a 1/30 s frame of one-solve implicit Euler
// (pcg-multigrid), vbd (20 sweeps) and xpbd (20 substeps of one sweep) on the drape with the
// smooth contact model, top row pinned, at n x n. Wall time (the threads' CPU time adds up);
// the speed-up is the 1-thread row over the 2-thread row. docs/performance/threads.md.
#include <benchmark/benchmark.h>

#include "core/parallel/parallel_for.hpp"
#include "experiments/benchmarks/bench_scenes.hpp"
#include "experiments/benchmarks/draped_cloth.hpp"
#include "integrators/explicit/leapfrog.hpp"
#include "integrators/registry/registry.hpp"

namespace drape {
namespace {

// Sets the thread count for one benchmark and restores it after.
class ThreadCount {
 public:
  explicit ThreadCount(benchmark::State& state) : m_before(thread_count()) {
    set_thread_count(static_cast<int>(state.range(1)));
    state.counters["threaded"] = runs_threaded(state.range(0) * state.range(0), threaded_particles_from);
  }
  ~ThreadCount() { set_thread_count(m_before); }
  ThreadCount(const ThreadCount&) = delete;
  ThreadCount& operator=(const ThreadCount&) = delete;

 private:
  int m_before;
};

void BM_ThreadsForces(benchmark::State& state) {
  const ThreadCount threads(state);
  Eigen::VectorXd y;
  auto system = bench::draped_cloth(static_cast<int>(state.range(0)), y);
  const Eigen::Index n3 = 3 * system->num_particles();
  Eigen::VectorXd f(n3);
  for (auto _ : state) {
    system->forces(ConstVecMap(y.data(), n3), ConstVecMap(y.data() + n3, n3), VecMap(f.data(), n3));
    benchmark::DoNotOptimize(f.data());
  }
}
BENCHMARK(BM_ThreadsForces)
    ->ArgsProduct({{32, 48, 64, 128}, {1, 2}})
    ->UseRealTime()
    ->Unit(benchmark::kMicrosecond);

void BM_ThreadsLeapfrogStep(benchmark::State& state) {
  const ThreadCount threads(state);
  Eigen::VectorXd y;
  auto system = bench::settled_drape(static_cast<int>(state.range(0)), y);
  Leapfrog leapfrog(*system, 1e-4);
  leapfrog.reset(0.0, y);
  for (auto _ : state) leapfrog.step(1e9);
}
BENCHMARK(BM_ThreadsLeapfrogStep)
    ->ArgsProduct({{32, 48, 64, 128}, {1, 2}})
    ->UseRealTime()
    ->Unit(benchmark::kMicrosecond);

// One frame per benchmark iteration, continuing from the last.
void frames(benchmark::State& state, IntegratorOptions options) {
  const ThreadCount threads(state);
  Eigen::VectorXd y;
  auto system = bench::smooth_drape(static_cast<int>(state.range(0)), y);
  options.dt = 1.0 / 30.0;
  auto method = make_integrator(options, *system);
  method->reset(0.0, y);
  for (auto _ : state) method->step(1e9);
}

void BM_ThreadsImplicitEulerFrame(benchmark::State& state) {
  IntegratorOptions options;
  options.name = "implicit-euler";
  frames(state, options);
}

void BM_ThreadsVbdFrame(benchmark::State& state) {
  IntegratorOptions options;
  options.name = "vbd";
  options.settings = {{"iterations", 20}};
  frames(state, options);
}

void BM_ThreadsXpbdFrame(benchmark::State& state) {
  IntegratorOptions options;
  options.name = "xpbd";
  options.settings = {{"substeps", 20}, {"iterations", 1}};
  frames(state, options);
}

BENCHMARK(BM_ThreadsImplicitEulerFrame)
    ->ArgsProduct({{32, 64, 128}, {1, 2}})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ThreadsVbdFrame)
    ->ArgsProduct({{32, 64, 128}, {1, 2}})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ThreadsXpbdFrame)
    ->ArgsProduct({{32, 64, 128}, {1, 2}})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace drape
