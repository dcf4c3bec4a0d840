// drapelab_bench: force evaluation, one leap-frog step and the nearest-object-particle query on
// the built-in dress form (80 x 32 object particles). Not part of ctest; see docs/performance.md.
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>

#include "core/dummy_sources.hpp"
#include "integrators/leapfrog.hpp"

namespace drape {
namespace {

constexpr double pi = 3.14159265358979323846;

const std::shared_ptr<const Dummy>& dress_form() {
  static const auto dummy = std::make_shared<const Dummy>(
      make_dummy(nlohmann::json{{"builtin", "dress-form"}}, "bench", "dummy", "."));
  return dummy;
}

// An n x n cloth wrapped around the dress form from the shoulders down, every particle half a
// threshold outside the surface: the draped state, where every collision query finds contact.
std::unique_ptr<ClothSystem> draped_cloth(int n, Eigen::VectorXd& y) {
  const Dummy& dummy = *dress_form();
  ClothParams p;
  p.rows = p.cols = n;
  p.spacing = 0.5 / n;
  p.particle_mass = 0.2 / (n * n);
  p.k_structural = 50.0;
  p.k_shear = 50.0;
  p.damping_spring = 0.01;
  p.damping_air = 0.001;
  p.origin = Vec3(0.0, 1.3, 0.2);
  ForceParams forces;
  forces.collision = {0.01, 1000.0};
  auto system = std::make_unique<ClothSystem>(build_cloth(p), dress_form(), forces);
  y = Eigen::VectorXd::Zero(system->size());
  const double y_top = dummy.sections().y.front() - 0.02;
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) {
      const double height = y_top - r * p.spacing;
      const double theta = 2.0 * pi * (c - n / 2) / n * 0.45;  // the front 160 degrees
      const Eigen::Vector2d axis = dummy.axis_at(height);
      const double radius = dummy.surface_radius(height, theta) + 0.5 * forces.collision.threshold;
      y.segment<3>(3 * (r * n + c)) =
          Vec3(axis.x() + radius * std::sin(theta), height, axis.y() + radius * std::cos(theta));
    }
  return system;
}

// Reports wall time per cloth particle per iteration in nanoseconds.
void report_per_particle(benchmark::State& state, int particles) {
  state.counters["ns_per_particle"] = benchmark::Counter(
      1e-9 * particles, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void BM_Forces(benchmark::State& state) {
  Eigen::VectorXd y;
  auto system = draped_cloth(static_cast<int>(state.range(0)), y);
  const Eigen::Index n3 = 3 * system->num_particles();
  Eigen::VectorXd f(n3);
  for (auto _ : state) {
    system->forces(ConstVecMap(y.data(), n3), ConstVecMap(y.data() + n3, n3), VecMap(f.data(), n3));
    benchmark::DoNotOptimize(f.data());
  }
  report_per_particle(state, system->num_particles());
}
BENCHMARK(BM_Forces)->Arg(32)->Arg(64)->Arg(128)->Unit(benchmark::kMicrosecond);

void BM_LeapfrogStep(benchmark::State& state) {
  Eigen::VectorXd y;
  auto system = draped_cloth(static_cast<int>(state.range(0)), y);
  Leapfrog leapfrog(*system, 1e-4);
  leapfrog.reset(0.0, y);
  for (auto _ : state) leapfrog.step(1e9);
  report_per_particle(state, system->num_particles());
}
BENCHMARK(BM_LeapfrogStep)->Arg(32)->Arg(64)->Arg(128)->Unit(benchmark::kMicrosecond);

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
