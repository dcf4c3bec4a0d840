// drapelab_bench: vbd's frame (one 1/30 s step) at 10 and 100 sweeps on the free sheet and on
// the sheet draped on the dress form with the smooth contact model, at 32 x 32, 64 x 64 and
// 128 x 128, top row pinned; and the cost of reaching converged backward Euler's accuracy on
// a frame of the swinging sheet with vbd and with the line-search Newton (implicit-euler,
// solve = converged). See docs/integrators/vbd.md.
#include <benchmark/benchmark.h>

#include <cmath>

#include "experiments/benchmarks/draped_cloth.hpp"
#include "integrators/registry/registry.hpp"
#include "tests/support/backward_euler_reference.hpp"

namespace drape {
namespace {

constexpr double frame = 1.0 / 30.0;

std::unique_ptr<ClothSystem> pinned_sheet(int n, bool draped, Eigen::VectorXd& y) {
  auto system = bench::draped_cloth(n, y, draped, CollisionModel::smooth);
  for (int col = 0; col < n; ++col) system->constraints().fix_at(col, y.segment<3>(3 * col));
  return system;
}

IntegratorOptions vbd_options(long iterations) {
  IntegratorOptions o;
  o.name = "vbd";
  o.dt = frame;
  o.settings = {{"iterations", iterations}};
  return o;
}

// One frame per benchmark iteration, continuing from the last.
void vbd_frames(benchmark::State& state, bool draped, long iterations) {
  Eigen::VectorXd y;
  auto system = pinned_sheet(static_cast<int>(state.range(0)), draped, y);
  auto method = make_integrator(vbd_options(iterations), *system);
  method->reset(0.0, y);
  for (auto _ : state) method->step(1e9);
  state.counters["us_per_sweep"] =
      benchmark::Counter(static_cast<double>(method->counters().newton_iters) * 1e-6,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

// The frame from y by `options`: its end state.
Eigen::VectorXd first_frame(ClothSystem& system, const Eigen::VectorXd& y,
                            const IntegratorOptions& options) {
  auto method = make_integrator(options, system);
  method->reset(0.0, y);
  method->step(frame);
  return method->state();
}

// Converged backward Euler's stopping test (implicit_euler.cpp): the weighted RMS norm of a
// 6N difference with ARKODE's weights 1 / (rtol |y_n| + atol) of the frame's start.
double weighted_norm(const Eigen::VectorXd& a, const Eigen::VectorXd& b, const Eigen::VectorXd& y,
                     double rtol, double atol) {
  const Eigen::ArrayXd weights = 1.0 / (rtol * y.array().abs() + atol);
  return std::sqrt(((a - b).array() * weights).square().mean());
}

// Times the frame of `options` from y; `error` is its weighted distance to the reference.
void time_first_frame(benchmark::State& state, ClothSystem& system, const Eigen::VectorXd& y,
                      const IntegratorOptions& options, double error) {
  for (auto _ : state) benchmark::DoNotOptimize(first_frame(system, y, options).data());
  state.counters["weighted_error"] = error;
}

// The swinging sheet of the tests at n x n (tests/support/swinging_sheet.hpp, draped_cloth's
// mass and stiffness): horizontal, pinned at the two corners of its first row, after three
// converged frames from rest, so that the frame moves (a frame from rest has zero velocities,
// whose error weights 1 / atol ask for 1e-8 m/s).
std::unique_ptr<ClothSystem> swinging_sheet(int n, Eigen::VectorXd& y) {
  ClothParams p;
  p.rows = p.cols = n;
  p.spacing = 0.5 / n;
  p.particle_mass = 0.2 / (n * n);
  p.k_structural = p.k_shear = 50.0;
  p.damping_spring = 0.01;
  p.damping_air = 0.001;
  p.origin = Vec3(-0.25, 1.3, 0.0);
  p.row_dir = Vec3(0.0, 0.0, 1.0);
  auto system = std::make_unique<ClothSystem>(build_cloth(p), nullptr, ForceParams{});
  const Eigen::VectorXd& rest = system->cloth().rest_positions;
  system->constraints().fix_at(0, rest.segment<3>(0));
  system->constraints().fix_at(n - 1, rest.segment<3>(3 * (n - 1)));
  auto method = make_integrator(testing::converged_backward_euler(frame, 1e-10, 1e-12), *system);
  method->reset(0.0, system->initial_state(0.0));
  for (int k = 0; k < 3; ++k) method->step(1e9);
  y = method->state();
  return system;
}

// Converged backward Euler at its default tolerances (rtol 1e-4, atol 1e-7: it stops once its
// update's weighted RMS norm, times its rate factor, is at most 0.1) against a tight reference
// (rtol 1e-10, atol 1e-12), on the swinging sheet's fourth frame; then vbd with the fewest
// sweeps, by doubling from 1 up to 2^14, whose frame is within the same tolerance of the
// reference (weighted RMS norm <= 0.1); both timed. (On draped_cloth's sheets, free or on the
// dress form, vbd converges to another stationary point of the frame's potential than Newton's,
// centimetres away: docs/integrators/vbd.md.)
void reach_backward_euler(benchmark::State& state, bool with_vbd) {
  constexpr double rtol = 1e-4, atol = 1e-7, tolerance = 0.1;
  constexpr long max_sweeps = 16384;
  Eigen::VectorXd y;
  auto system = swinging_sheet(static_cast<int>(state.range(0)), y);
  const Eigen::VectorXd reference =
      first_frame(*system, y, testing::converged_backward_euler(frame, 1e-10, 1e-12));
  const IntegratorOptions newton = testing::converged_backward_euler(frame, rtol, atol);
  if (!with_vbd) {
    const double error = weighted_norm(first_frame(*system, y, newton), reference, y, rtol, atol);
    time_first_frame(state, *system, y, newton, error);
    return;
  }
  double error = 0.0;
  for (long iterations = 1; iterations <= max_sweeps; iterations *= 2) {
    const IntegratorOptions o = vbd_options(iterations);
    error = weighted_norm(first_frame(*system, y, o), reference, y, rtol, atol);
    if (error <= tolerance) {
      time_first_frame(state, *system, y, o, error);
      state.counters["iterations"] = static_cast<double>(iterations);
      return;
    }
  }
  state.SkipWithError(("not within tolerance after " + std::to_string(max_sweeps) +
                       " sweeps: weighted error " + std::to_string(error))
                          .c_str());
}

const bool registered = [] {
  for (const bool draped : {false, true})
    for (const long iterations : {10L, 100L})
      benchmark::RegisterBenchmark(
          (std::string("BM_VbdFrame/") + (draped ? "draped" : "free") + "/" +
           std::to_string(iterations))
              .c_str(),
          [draped, iterations](benchmark::State& state) { vbd_frames(state, draped, iterations); })
          ->Arg(32)
          ->Arg(64)
          ->Arg(128)
          ->Unit(benchmark::kMillisecond);
  for (const bool with_vbd : {false, true})
    benchmark::RegisterBenchmark(
        (std::string("BM_ReachBackwardEuler/") + (with_vbd ? "vbd" : "newton")).c_str(),
        [with_vbd](benchmark::State& state) { reach_backward_euler(state, with_vbd); })
        ->Arg(16)
        ->Arg(32)
        ->Unit(benchmark::kMillisecond);
  return true;
}();

}  // namespace
}  // namespace drape
