// drapelab_bench: the 1/30 s step of the implicit methods at 32 x 32, 64 x 64 and
// 128 x 128: implicit-euler (one linearised solve, its default pcg-multigrid) and arkode-dirk
// with the line-search Newton, SDIRK2 (ARKODE_SDIRK_2_1_2, and Alexander's as a user table) and
// a third-order ESDIRK (ARKODE_ESDIRK325L2SA_5_2_3), on a free swinging sheet and on the dress
// form with the smooth contact model; Alexander's SDIRK2 also with looser stage tolerances. See
// docs/performance/implicit-step.md and docs/performance/sdirk-step.md.
//
// Each benchmark takes a few steps before timing (the first step holds the one-time setup:
// patterns, multigrid levels, ARKODE's memory, first touch of the arrays), then times a fixed
// number, so that a run stays bounded at 128 x 128 and measures a warmed-up solver. The CG
// iterations of implicit-euler follow the motion (3 to 17 a step on the sheet when measured
// with the last dv as CG's start), so it times
// 60 steps, 2 s of motion (docs/performance/implicit-step.md); an ARKODE step costs seconds.
#include <benchmark/benchmark.h>

#include "experiments/benchmarks/bench_scenes.hpp"
#include "integrators/registry/registry.hpp"

namespace drape {
namespace {

constexpr double frame = 1.0 / 30.0;

struct StepCase {
  const char* label;
  const char* integrator;
  const char* table;  // an ARKODE table's name, an inline user table (JSON), or "" for none
  const char* linear_solver;
  const char* exact_solve;  // the line search's local phase: "lu" or "bicgstab"
  int warm_up, timed;       // steps before timing, timed steps
  // The stage tolerances (IntegratorOptions::rtol, atol); 0 keeps the run's default.
  double rtol = 0.0, atol = 0.0;
};

// Alexander's two-stage SDIRK (1977, SIAM J. Numer. Anal. 14(6); Hairer and Wanner, Solving
// ODEs II, table IV.6.5 with gamma = 1 - 1/sqrt(2)): L-stable and stiffly accurate, each stage a
// backward-Euler-like solve over gamma h = 0.29 h. ARKODE's SDIRK_2_1_2 is another method
// (A = [1 0; -1 1], docs/findings/energy_gaining_tables.md "Which tables gain energy"), each
// stage over h.
constexpr const char* alexander_sdirk2 =
    R"({"c": [0.29289321881345254, 1], "A": [[0.29289321881345254, 0],)"
    R"( [0.70710678118654752, 0.29289321881345254]],)"
    R"( "b": [0.70710678118654752, 0.29289321881345254], "q": 2})";

const StepCase cases[] = {
    {"implicit-euler", "implicit-euler", "", "", "", 3, 60},
    {"sdirk2", "arkode-dirk", "ARKODE_SDIRK_2_1_2", "", "lu", 1, 3},
    {"sdirk2/pcg-multigrid", "arkode-dirk", "ARKODE_SDIRK_2_1_2", "pcg-multigrid", "lu", 1, 3},
    {"alexander-sdirk2/pcg-multigrid", "arkode-dirk", alexander_sdirk2, "pcg-multigrid", "lu", 1,
     3},
    {"alexander-sdirk2/bicgstab", "arkode-dirk", alexander_sdirk2, "pcg-multigrid", "bicgstab", 1,
     3},
    // The same step with looser stage tolerances (rtol 1e-2 against the default 1e-4, atol 1e-5
    // and 1e-4 against 1e-7): how much of its cost the default tolerances ask for.
    {"alexander-sdirk2/bicgstab/rtol1e-2-atol1e-5", "arkode-dirk", alexander_sdirk2,
     "pcg-multigrid", "bicgstab", 1, 3, 1e-2, 1e-5},
    {"alexander-sdirk2/bicgstab/rtol1e-2-atol1e-4", "arkode-dirk", alexander_sdirk2,
     "pcg-multigrid", "bicgstab", 1, 3, 1e-2, 1e-4},
    {"esdirk3", "arkode-dirk", "ARKODE_ESDIRK325L2SA_5_2_3", "", "lu", 1, 3},
};

using Scene = std::unique_ptr<ClothSystem> (*)(int, Eigen::VectorXd&);

void run_implicit_steps(benchmark::State& state, Scene scene, const StepCase& c) {
  Eigen::VectorXd y;
  auto system = scene(static_cast<int>(state.range(0)), y);
  IntegratorOptions options;
  options.name = c.integrator;
  options.dt = frame;
  if (c.table[0] == '{')
    options.user_table = nlohmann::json::parse(c.table);
  else
    options.table = c.table;
  options.linear_solver = c.linear_solver;
  options.nonlinear_solver = options.name == "arkode-dirk" ? "line-search" : "";
  options.exact_solve = c.exact_solve;
  if (c.rtol > 0.0) options.rtol = c.rtol;
  if (c.atol > 0.0) options.atol = c.atol;
  auto method = make_integrator(options, *system);
  method->reset(0.0, y);
  IntegratorCounters before;
  try {
    for (int k = 0; k < c.warm_up; ++k) method->step(1e9);
    before = method->counters();
    for (auto _ : state) method->step(1e9);
  } catch (const IntegratorFailure& failure) {
    state.SkipWithError(failure.what());
    return;
  }
  const IntegratorCounters& after = method->counters();
  const auto per_step = [&](long IntegratorCounters::*counter) {
    return benchmark::Counter(static_cast<double>(after.*counter - before.*counter),
                              benchmark::Counter::kAvgIterations);
  };
  state.counters["newton_per_step"] = per_step(&IntegratorCounters::newton_iters);
  state.counters["linear_per_step"] = per_step(&IntegratorCounters::linear_iters);
  state.counters["backtracks_per_step"] = per_step(&IntegratorCounters::line_search_backtracks);
  state.counters["halvings_per_step"] = per_step(&IntegratorCounters::step_halvings);
}

const bool registered = [] {
  const std::pair<const char*, Scene> scenes[] = {{"sheet", bench::swinging_sheet},
                                                  {"dress-form-smooth", bench::smooth_drape}};
  for (const auto& [scene_label, scene] : scenes)
    for (const StepCase& c : cases)
      benchmark::RegisterBenchmark(
          (std::string("BM_ImplicitStep/") + scene_label + "/" + c.label).c_str(),
          [scene = scene, c](benchmark::State& state) { run_implicit_steps(state, scene, c); })
          ->Arg(32)
          ->Arg(64)
          ->Arg(128)
          ->Iterations(c.timed)
          ->Unit(benchmark::kMillisecond);
  const StepCase& implicit_euler = cases[0];
  benchmark::RegisterBenchmark(
      "BM_ImplicitStep/sheet-equal-particles/implicit-euler",
      [&](benchmark::State& state) { run_implicit_steps(state, bench::sheet_of_equal_particles, implicit_euler); })
      ->Arg(32)
      ->Arg(64)
      ->Arg(128)
      ->Iterations(implicit_euler.timed)
      ->Unit(benchmark::kMillisecond);
  return true;
}();

}  // namespace
}  // namespace drape
