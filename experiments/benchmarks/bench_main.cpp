// drapelab_bench: force evaluation, one leap-frog step and the nearest-object-particle query on
// the built-in dress form (80 x 32 object particles). Not part of ctest; see
// docs/performance/leapfrog-step.md.
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include "core/forces/grid_spring_forces.hpp"
#include "core/parallel/parallel_for.hpp"
#include "experiments/benchmarks/draped_cloth.hpp"
#include "integrators/explicit/leapfrog.hpp"

namespace drape {
namespace {

using bench::dress_form;
using bench::draped_cloth;
using bench::pi;

// The tables of docs/performance/ are of one thread (CPU time), bench_threads.cpp's aside: the
// hot loops would otherwise take every core (core/parallel) from the start of the program.
[[maybe_unused]] const bool one_thread = (set_thread_count(1), true);

// Reports wall time per cloth particle per iteration in nanoseconds.
void report_per_particle(benchmark::State& state, int particles) {
  state.counters["ns_per_particle"] = benchmark::Counter(
      1e-9 * particles, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void BM_Forces(benchmark::State& state) {
  Eigen::VectorXd y;
  auto system = draped_cloth(static_cast<int>(state.range(0)), y, state.range(1) != 0);
  const Eigen::Index n3 = 3 * system->num_particles();
  Eigen::VectorXd f(n3);
  for (auto _ : state) {
    system->forces(ConstVecMap(y.data(), n3), ConstVecMap(y.data() + n3, n3), VecMap(f.data(), n3));
    benchmark::DoNotOptimize(f.data());
  }
  report_per_particle(state, system->num_particles());
  if (system->dummy()) state.counters["in_contact"] = bench::contact_fraction(*system, y);
}
// Second argument: 1 with the dress form (collisions), 0 springs, gravity and damping alone.
BENCHMARK(BM_Forces)->ArgsProduct({{32, 64, 128}, {1, 0}})->Unit(benchmark::kMicrosecond);

// Steps of the settled drape (bench::settled_drape); `in_contact`: the fraction of particles
// within the collision threshold at the end.
void BM_LeapfrogStep(benchmark::State& state) {
  Eigen::VectorXd y;
  auto system = bench::settled_drape(static_cast<int>(state.range(0)), y);
  Leapfrog leapfrog(*system, 1e-4);
  leapfrog.reset(0.0, y);
  for (auto _ : state) leapfrog.step(1e9);
  report_per_particle(state, system->num_particles());
  state.counters["in_contact"] = bench::contact_fraction(*system, leapfrog.state());
}
BENCHMARK(BM_LeapfrogStep)->Arg(32)->Arg(64)->Arg(128)->Unit(benchmark::kMicrosecond);

// The yardstick, "a plain spring loop without collisions", so that the leap-frog step can
// be compared with it on whatever machine runs the benchmarks: one symplectic step of the wrapped
// cloth's springs (elastic force only, listed springs, interleaved xyz), gravity, no damping,
// no object, no constraints. Not a model the program runs.
void BM_PlainSpringLoop(benchmark::State& state) {
  Eigen::VectorXd y;
  auto system = draped_cloth(static_cast<int>(state.range(0)), y, false);
  const SpringList& springs = system->cloth().springs;
  const Eigen::Index n3 = 3 * system->num_particles();
  Eigen::VectorXd x = y.head(n3), v = Eigen::VectorXd::Zero(n3), f(n3);
  const double dt = 1e-4, dt_over_m = dt / system->particle_mass();
  const Vec3 dv_gravity = dt * system->params().gravity;
  for (auto _ : state) {
    f.setZero();
    for (Eigen::Index s = 0; s < springs.size(); ++s) {
      const int i = springs.first[s], j = springs.second[s];
      const Vec3 d = x.segment<3>(3 * j) - x.segment<3>(3 * i);
      const double length = d.norm();
      const Vec3 fi = (springs.stiffness[s] * (length - springs.rest[s]) / length) * d;
      f.segment<3>(3 * i) += fi;
      f.segment<3>(3 * j) -= fi;
    }
    for (Eigen::Index i = 0; i < n3; i += 3) {
      v.segment<3>(i) += dt_over_m * f.segment<3>(i) + dv_gravity;
      x.segment<3>(i) += dt * v.segment<3>(i);
    }
    benchmark::DoNotOptimize(x.data());
  }
  report_per_particle(state, system->num_particles());
}
BENCHMARK(BM_PlainSpringLoop)->Arg(64)->Unit(benchmark::kMicrosecond);

// The spring loop's kernel alone (every stencil, damped), by instruction set: 0 SSE2, 1 AVX (the
// one the program picks on processors that have it).
void BM_SpringKernel(benchmark::State& state) {
  const bool avx = state.range(1) != 0;
  if (avx && !spring_kernel::has_avx()) {
    state.SkipWithError("this processor has no AVX");
    return;
  }
  Eigen::VectorXd y;
  auto system = draped_cloth(static_cast<int>(state.range(0)), y);
  const Cloth& cloth = system->cloth();
  const Eigen::Index n = cloth.size();
  // The layout GridSpringForces uses.
  StaggeredColumns columns(n, 3);
  Components x = columns.group(0), v = columns.group(1), force = columns.group(2);
  to_components(y.head(3 * n), x);
  v.setZero();
  Eigen::ArrayX3d row(cloth.params.cols, 3);
  const spring_kernel::Arrays arrays = kernel_arrays(x, v, force, row);
  const auto add = avx ? spring_kernel::add_avx : spring_kernel::add_sse2;
  const int rows = cloth.params.rows, cols = cloth.params.cols;
  for (auto _ : state) {
    force.setZero();
    for (const SpringStencil& s : cloth.stencils)
      add(s, rows, cols, cloth.params.damping_spring, arrays);
    benchmark::DoNotOptimize(force.data());
  }
  report_per_particle(state, static_cast<int>(n));
}
BENCHMARK(BM_SpringKernel)->ArgsProduct({{64}, {0, 1}})->Unit(benchmark::kMicrosecond);

// Query points in a 2 cm shell around the dress form, as cloth particles in contact are.
std::vector<Vec3> shell_points(int count) {
  const Dummy& dummy = *dress_form();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> height(dummy.sections().y.back(), dummy.sections().y.front());
  std::uniform_real_distribution<double> angle(0.0, 2.0 * pi), gap(-0.005, 0.02);
  std::vector<Vec3> points;
  for (int k = 0; k < count; ++k) {
    const double h = height(rng), th = angle(rng);
    const Eigen::Vector2d axis = dummy.axis_at(h);
    const double r = dummy.surface_radius(h, th) + gap(rng);
    points.emplace_back(axis.x() + r * std::sin(th), h, axis.y() + r * std::cos(th));
  }
  return points;
}

template <class Query>
void run_queries(benchmark::State& state, Query&& query) {
  const auto points = shell_points(4096);
  std::size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(query(points[k]));
    k = (k + 1) % points.size();
  }
}

void BM_NearestWithinThreshold(benchmark::State& state) {
  run_queries(state, [](const Vec3& p) { return dress_form()->nearest_within(p, 0.01); });
}
BENCHMARK(BM_NearestWithinThreshold);

void BM_NearestExact(benchmark::State& state) {
  run_queries(state, [](const Vec3& p) { return dress_form()->nearest(p); });
}
BENCHMARK(BM_NearestExact);

void BM_NearestBruteForce(benchmark::State& state) {
  run_queries(state, [](const Vec3& p) { return dress_form()->nearest_brute_force(p); });
}
BENCHMARK(BM_NearestBruteForce);

void BM_InsideTest(benchmark::State& state) {
  run_queries(state, [](const Vec3& p) { return dress_form()->inside(p); });
}
BENCHMARK(BM_InsideTest);

}  // namespace
}  // namespace drape
