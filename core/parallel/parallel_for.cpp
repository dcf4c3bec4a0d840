#include "core/parallel/parallel_for.hpp"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <stdexcept>

namespace drape {

namespace {

// 0: not set, all processors.
std::atomic<int> g_threads{0};

}  // namespace

int available_processors() { return std::max(1, omp_get_num_procs()); }

int thread_count() {
  const int n = g_threads.load(std::memory_order_relaxed);
  return n > 0 ? n : available_processors();
}

void set_thread_count(int n) {
  if (n < 1) throw std::invalid_argument("thread count below 1");
  g_threads.store(n, std::memory_order_relaxed);
}

namespace detail {

void parallel_blocks(std::ptrdiff_t n, std::ptrdiff_t serial_below, BlockBody body) {
  if (!runs_threaded(n, serial_below)) {
    if (n > 0) body(0, n);
    return;
  }
  const std::ptrdiff_t threads = std::min<std::ptrdiff_t>(thread_count(), n);
#pragma omp parallel for schedule(static, 1) num_threads(static_cast<int>(threads))
  for (std::ptrdiff_t t = 0; t < threads; ++t) body(n * t / threads, n * (t + 1) / threads);
}

}  // namespace detail

}  // namespace drape
