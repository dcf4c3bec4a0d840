// drapelab_bench: the kernels of one CG iteration of `pcg-multigrid` on an n x n grid's reduced
// system S (9-point block pattern, random SPD couplings, tests/support/grid_matrix.hpp): the
// product by S and one multigrid cycle, and forming the coarse levels. The counter gives the
// cost per fine block row, so that growth beyond the particle count (cache) shows as a growing
// `ns_per_row`. See docs/performance/implicit-step.md.
#include <benchmark/benchmark.h>

#include <functional>

#include "integrators/linear/grid_multigrid.hpp"
#include "tests/support/grid_matrix.hpp"

namespace drape {
namespace {

using Kernel = std::function<void(const detail::SymmetricBlockMatrix&, detail::GridMultigrid&,
                                  const Eigen::VectorXd&, Eigen::VectorXd&)>;

// Times `kernel` on the n x n grid's matrix, its multigrid levels formed, with a random vector.
void time_on_grid(benchmark::State& state, const Kernel& kernel) {
  const int n = static_cast<int>(state.range(0));
  const detail::SymmetricBlockMatrix a = testing::grid_matrix(n, n, 1);
  detail::GridMultigrid multigrid;
  multigrid.build(a, n, n);
  multigrid.update(a);
  const Eigen::VectorXd r = Eigen::VectorXd::Random(3 * n * n);
  Eigen::VectorXd out(r.size());
  for (auto _ : state) {
    kernel(a, multigrid, r, out);
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["ns_per_row"] = benchmark::Counter(
      1e-9 * n * n, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void BM_ReducedProduct(benchmark::State& state) {
  time_on_grid(state, [](const auto& a, auto&, const auto& r, auto& out) { a.multiply(r, out); });
}
void BM_MultigridCycle(benchmark::State& state) {
  time_on_grid(state,
               [](const auto& a, auto& mg, const auto& r, auto& out) { mg.apply(a, r, out); });
}
void BM_MultigridUpdate(benchmark::State& state) {
  time_on_grid(state, [](const auto& a, auto& mg, const auto&, auto&) { mg.update(a); });
}
BENCHMARK(BM_ReducedProduct)->Arg(32)->Arg(64)->Arg(128)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MultigridCycle)->Arg(32)->Arg(64)->Arg(128)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MultigridUpdate)->Arg(32)->Arg(64)->Arg(128)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace drape
