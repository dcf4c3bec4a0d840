// drapelab_bench: one step of every integrator on the draped cloth (top row pinned) at 32 x 32,
// 64 x 64 and 128 x 128, and the cost of one right-hand side inside each of them. Explicit
// methods step at 1e-4 s (their cost per step hardly depends on it), implicit ones at 1/30 s
// (arkode-dirk and arkode-imex also adaptive, up to 1/30 s).
// See docs/performance/integrator-step.md.
#include <benchmark/benchmark.h>

#include "experiments/benchmarks/draped_cloth.hpp"
#include "integrators/registry/registry.hpp"

namespace drape {
namespace {

struct BenchCase {
  const char* label;
  const char* integrator;
  const char* linear_solver;
  double dt;              // fixed step, or the largest step of an adaptive run
  bool adaptive = false;  // error-controlled steps (rtol 1e-4), starting at 1e-4 s
};

void run_steps(benchmark::State& state, const BenchCase& c) {
  Eigen::VectorXd y;
  const int n = static_cast<int>(state.range(0));
  auto system = bench::draped_cloth(n, y);
  for (int col = 0; col < n; ++col) system->constraints().fix_at(col, y.segment<3>(3 * col));
  IntegratorOptions options;
  options.name = c.integrator;
  options.dt = c.adaptive ? 1e-4 : c.dt;
  options.adaptive = c.adaptive;
  options.max_dt = c.adaptive ? c.dt : 0.0;
  options.linear_solver = c.linear_solver;
  auto method = make_integrator(options, *system);
  method->reset(0.0, y);
  try {
    for (auto _ : state) method->step(1e9);
  } catch (const IntegratorFailure& failure) {
    state.SkipWithError(failure.what());
    return;
  }
  const IntegratorCounters& counters = method->counters();
  const auto steps = static_cast<double>(counters.steps);
  state.counters["rhs_per_step"] = static_cast<double>(counters.rhs_evals) / steps;
  state.counters["newton_per_step"] = static_cast<double>(counters.newton_iters) / steps;
  state.counters["linear_per_step"] = static_cast<double>(counters.linear_iters) / steps;
  state.counters["mean_dt"] = method->time() / steps;
  // Fixed-step ARKODE runs halve a step whose Newton solve fails (docs/integrators/arkode.md): a
  // benchmark iteration is then one step of dt covered by several shorter ones.
  state.counters["halvings_per_iteration"] = benchmark::Counter(
      static_cast<double>(counters.step_halvings), benchmark::Counter::kAvgIterations);
  // Wall time per right-hand side: the step's whole cost (vector operations and solves
  // included) spread over its force evaluations.
  state.counters["us_per_rhs"] = benchmark::Counter(
      static_cast<double>(counters.rhs_evals) * 1e-6,
      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

const BenchCase cases[] = {
    {"leapfrog", "leapfrog", "", 1e-4},
    {"symplectic-euler", "symplectic-euler", "", 1e-4},
    {"arkode-erk", "arkode-erk", "", 1e-4},
    {"implicit-euler/pcg-reduced", "implicit-euler", "pcg-reduced", 1.0 / 30.0},
    {"implicit-euler/pcg-multigrid", "implicit-euler", "pcg-multigrid", 1.0 / 30.0},
    {"implicit-euler/sparse-direct", "implicit-euler", "sparse-direct", 1.0 / 30.0},
    {"arkode-dirk/pcg-reduced", "arkode-dirk", "pcg-reduced", 1.0 / 30.0},
    {"arkode-dirk/sparse-direct", "arkode-dirk", "sparse-direct", 1.0 / 30.0},
    {"arkode-imex/pcg-reduced", "arkode-imex", "pcg-reduced", 1.0 / 30.0},
    {"arkode-imex/sparse-direct", "arkode-imex", "sparse-direct", 1.0 / 30.0},
    // At fixed 1/30 s their Newton iterations fail on the draped cloth unless the step is halved
    // (docs/performance/integrator-step.md): the same methods with error-controlled steps up to
    // 1/30 s.
    {"arkode-dirk/pcg-reduced/adaptive", "arkode-dirk", "pcg-reduced", 1.0 / 30.0, true},
    {"arkode-imex/pcg-reduced/adaptive", "arkode-imex", "pcg-reduced", 1.0 / 30.0, true},
    {"arkode-dirk/pcg-multigrid/adaptive", "arkode-dirk", "pcg-multigrid", 1.0 / 30.0, true},
    {"arkode-imex/pcg-multigrid/adaptive", "arkode-imex", "pcg-multigrid", 1.0 / 30.0, true},
};

const bool registered = [] {
  for (const BenchCase& c : cases)
    benchmark::RegisterBenchmark((std::string("BM_IntegratorStep/") + c.label).c_str(),
                                 [c](benchmark::State& state) { run_steps(state, c); })
        ->Arg(32)
        ->Arg(64)
        ->Arg(128)
        ->Unit(benchmark::kMillisecond);
  return true;
}();

}  // namespace
}  // namespace drape
