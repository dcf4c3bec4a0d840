// drapelab_bench: the cost of reaching converged backward Euler's step to 1e-4 m and 1e-6 m
// (largest particle distance) on the same 1/30 s frame (converged_cost.hpp: the fourth frame of
// the swinging sheet and of the smooth drape, 32 x 32 and 64 x 64) with projective-dynamics and
// vbd, plain and Chebyshev-accelerated, and with implicit-euler's line-search Newton; and where
// PD and VBD end after the cap (BM_ConvergedCostEndPoint). See docs/performance/converged-cost.md.
//
// Each benchmark first finds, untimed and once per process, the fewest iterations (PD, VBD) or
// the loosest tolerance (the Newton) whose frame is within the distance of the reference, then
// times that frame: each timed iteration builds a fresh integrator and resets it (paused) and
// times its one step, so the timed step computes exactly the frame the search measured (PD's
// contact set and the Newton's CG start persist in an integrator; its factorisation and setup
// are in the step).
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <tuple>

#include "experiments/benchmarks/converged_cost.hpp"
#include "integrators/newton/incremental_potential.hpp"

namespace drape {
namespace {

using bench::CostScene;
using bench::IteratedMethod;

// The iteration cap: a count PD or VBD has not got within the distance by is reported as not
// reached, with the distance there.
constexpr long cap = 5000;

// One frame per scene and size, built once (the reference solves take seconds at 64 x 64).
const bench::CostFrame& frame_of(CostScene scene, int n) {
  static std::map<std::pair<CostScene, int>, bench::CostFrame> frames;
  auto it = frames.find({scene, n});
  if (it == frames.end()) it = frames.emplace(std::pair{scene, n}, cost_frame_of(scene, n)).first;
  return it->second;
}

// The distance of `method`'s frame at a count, each count computed once per process.
double distance_at(CostScene scene, int n, const IteratedMethod& method, long iterations) {
  static std::map<std::tuple<CostScene, int, const IteratedMethod*, long>, double> known;
  const auto key = std::tuple{scene, n, &method, iterations};
  auto it = known.find(key);
  if (it == known.end()) {
    const bench::CostFrame& f = frame_of(scene, n);
    const double d = bench::position_distance(
        bench::one_frame(*f.system, f.y, bench::iterated_options(method, iterations)),
        f.reference);
    it = known.emplace(key, d).first;
  }
  return it->second;
}

struct Fewest {
  long iterations = 0;     // 0: not within the distance at the cap
  double distance = 0.0;   // at `iterations`, or at the cap
  long below = 0;          // the largest count tried that is not within (0: none)
  double distance_below = std::numeric_limits<double>::quiet_NaN();
  std::string tried;       // "count: distance" of every count tried, in order
};

// Doubling from 1 until within `tolerance`, then bisection in log(count) down to a ratio of 1.2
// between the count within and the one not. Where the last two doublings' rate (the distance is
// linear in the count's exponent for a linear iteration) says the next ones would not get there
// before twice the cap, it tries the cap at once. Chebyshev's distance is not monotone in the
// count: the count found is within, `below` is not, and a count between may be either.
Fewest fewest_iterations(CostScene scene, int n, const IteratedMethod& method, double tolerance) {
  Fewest found;
  const auto d = [&](long k) {
    const double distance = distance_at(scene, n, method, k);
    char entry[48];
    std::snprintf(entry, sizeof entry, "%s%ld: %.2e", found.tried.empty() ? "" : ", ", k,
                  distance);
    found.tried += entry;
    return distance;
  };
  for (long k = 1;; k *= 2) {
    const long count = std::min(k, cap);
    const double here = d(count);
    if (here <= tolerance) {
      found.iterations = count;
      found.distance = here;
      break;
    }
    if (count == cap) {
      found.distance = here;
      return found;
    }
    if (found.below > 0) {
      const double rate =
          std::log(here / found.distance_below) / static_cast<double>(count - found.below);
      if (rate >= 0.0 ||
          static_cast<double>(count) + std::log(tolerance / here) / rate > 2.0 * cap)
        k = cap;
    }
    found.below = count;
    found.distance_below = here;
  }
  while (found.below > 0 && static_cast<double>(found.iterations) >
                                1.2 * static_cast<double>(found.below)) {
    const long mid = std::lround(std::sqrt(static_cast<double>(found.below) *
                                           static_cast<double>(found.iterations)));
    if (mid <= found.below || mid >= found.iterations) break;
    const double here = d(mid);
    if (here <= tolerance)
      found.iterations = mid, found.distance = here;
    else
      found.below = mid, found.distance_below = here;
  }
  return found;
}

// Times `options`' frame from the scene's y, fresh integrator each time; reports the distance
// of the timed frame and the counters of the last.
void time_frame(benchmark::State& state, const bench::CostFrame& f,
                const IntegratorOptions& options) {
  Eigen::VectorXd end;
  IntegratorCounters counters;
  for (auto _ : state) {
    state.PauseTiming();
    auto method = make_integrator(options, *f.system);
    method->reset(0.0, f.y);
    state.ResumeTiming();
    method->step(bench::cost_frame);
    state.PauseTiming();
    end = method->state();
    counters = method->counters();
    state.ResumeTiming();
  }
  state.counters["distance"] = bench::position_distance(end, f.reference);
  state.counters["newton_iters"] = static_cast<double>(counters.newton_iters);
  state.counters["cg_iters"] = static_cast<double>(counters.linear_iters);
}

void iterated_cost(benchmark::State& state, CostScene scene, int n, const IteratedMethod& method,
                   double tolerance) {
  const Fewest found = fewest_iterations(scene, n, method, tolerance);
  if (found.iterations == 0) {
    state.SkipWithError(("not within tolerance in " + std::to_string(cap) +
                         " iterations; distances (m) by count: " + found.tried)
                            .c_str());
    return;
  }
  time_frame(state, frame_of(scene, n), bench::iterated_options(method, found.iterations));
  state.counters["iterations"] = static_cast<double>(found.iterations);
  state.counters["iterations_not_within"] = static_cast<double>(found.below);
  state.counters["distance_not_within"] = found.distance_below;
}

// The Newton's accuracy is set by its tolerance: the loosest rtol of 1e-2, 1e-3, ..., 1e-10
// (atol = 1e-3 rtol, the defaults' ratio) whose frame is within the distance.
void newton_cost(benchmark::State& state, CostScene scene, int n, double tolerance) {
  static std::map<std::tuple<CostScene, int, double>, double> rtol_found;
  const bench::CostFrame& f = frame_of(scene, n);
  const auto key = std::tuple{scene, n, tolerance};
  if (rtol_found.count(key) == 0) {
    rtol_found[key] = 0.0;
    for (double rtol = 1e-2; rtol > 1e-11; rtol *= 0.1) {
      try {
        const Eigen::VectorXd end = bench::one_frame(
            *f.system, f.y,
            testing::converged_backward_euler(bench::cost_frame, rtol, 1e-3 * rtol));
        if (bench::position_distance(end, f.reference) <= tolerance) {
          rtol_found[key] = rtol;
          break;
        }
      } catch (const IntegratorFailure&) {
        // Not converged at this tolerance (a tighter one may): the next rung.
      }
    }
  }
  const double rtol = rtol_found[key];
  if (rtol == 0.0) {
    state.SkipWithError("not within tolerance at rtol 1e-10");
    return;
  }
  time_frame(state, f, testing::converged_backward_euler(bench::cost_frame, rtol, 1e-3 * rtol));
  state.counters["rtol"] = rtol;
}

// Where a method ends after the cap: its distance, the frame's incremental potential there minus
// at the reference (both with the spring damping's directions frozen at the reference, so that
// they are one function) and the largest entry of its gradient (kg m/s, with the directions at
// the point itself: zero at a backward Euler step). Computed once; the time means nothing.
void end_point(benchmark::State& state, CostScene scene, int n, const IteratedMethod& method) {
  const bench::CostFrame& f = frame_of(scene, n);
  IncrementalPotential potential(*f.system, ForceSplit::all);
  Eigen::VectorXd reference = f.reference, end = bench::one_frame(
      *f.system, f.y, bench::iterated_options(method, cap));
  Eigen::VectorXd gradient(end.size() / 2);
  potential.begin_stage(bench::cost_frame, bench::cost_frame, f.y, reference);
  potential.begin_stage(bench::cost_frame, bench::cost_frame, f.y, end);
  potential.freeze_damping(reference);
  const double difference = potential.value(end) - potential.value(reference);
  potential.freeze_damping(end);
  potential.gradient(end, gradient);
  for (auto _ : state) benchmark::DoNotOptimize(end.data());
  state.counters["distance"] = bench::position_distance(end, f.reference);
  state.counters["potential_minus_reference"] = difference;
  state.counters["gradient_inf"] = gradient.lpNorm<Eigen::Infinity>();
}

const bool registered = [] {
  for (const CostScene scene : {CostScene::sheet, CostScene::drape})
    for (const int n : {32, 64})
      for (const double tolerance : {1e-4, 1e-6}) {
        const std::string stem = std::string("BM_ConvergedCost/") + bench::scene_name(scene) +
                                 "/" + std::to_string(n) + "/" +
                                 (tolerance == 1e-4 ? "1e-4" : "1e-6") + "/";
        benchmark::RegisterBenchmark((stem + "newton").c_str(),
                                     [=](benchmark::State& state) {
                                       newton_cost(state, scene, n, tolerance);
                                     })
            ->Unit(benchmark::kMillisecond);
        for (const IteratedMethod& method : bench::iterated_methods)
          benchmark::RegisterBenchmark((stem + method.label).c_str(),
                                       [=, &method](benchmark::State& state) {
                                         iterated_cost(state, scene, n, method, tolerance);
                                       })
              ->Unit(benchmark::kMillisecond);
      }
  for (const CostScene scene : {CostScene::sheet, CostScene::drape})
    for (const IteratedMethod& method : bench::iterated_methods)
      benchmark::RegisterBenchmark((std::string("BM_ConvergedCostEndPoint/") +
                                    bench::scene_name(scene) + "/32/" + method.label)
                                       .c_str(),
                                   [=, &method](benchmark::State& state) {
                                     end_point(state, scene, 32, method);
                                   })
          ->Iterations(1);
  return true;
}();

}  // namespace
}  // namespace drape
