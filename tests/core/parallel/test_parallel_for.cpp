// parallel_for's blocks: they cover every item once, in contiguous ranges, on as many threads
// as set, and one block on the calling thread below the threshold.
#include <gtest/gtest.h>

#include <omp.h>

#include <algorithm>
#include <mutex>
#include <set>
#include <utility>
#include <vector>

#include "core/parallel/parallel_for.hpp"

namespace drape {
namespace {

struct Blocks {
  std::vector<std::pair<std::ptrdiff_t, std::ptrdiff_t>> ranges;
  std::set<int> threads;
};

Blocks blocks_of(std::ptrdiff_t n, std::ptrdiff_t serial_below) {
  Blocks b;
  std::mutex mutex;
  parallel_for(n, serial_below, [&](std::ptrdiff_t begin, std::ptrdiff_t end) {
    const std::lock_guard<std::mutex> lock(mutex);
    b.ranges.emplace_back(begin, end);
    b.threads.insert(omp_get_thread_num());
  });
  std::sort(b.ranges.begin(), b.ranges.end());
  return b;
}

TEST(ParallelFor, BlocksCoverEveryItemOnceOnTheThreadsSet) {
  const int before = thread_count();
  for (const int threads : {1, 2, 3, 4}) {
    set_thread_count(threads);
    for (const std::ptrdiff_t n : {2, 3, 7, 1000}) {
      const Blocks b = blocks_of(n, 0);
      const auto expected_blocks = static_cast<std::size_t>(std::min<std::ptrdiff_t>(threads, n));
      ASSERT_EQ(b.ranges.size(), expected_blocks) << threads << " threads, n = " << n;
      EXPECT_EQ(b.threads.size(), expected_blocks);
      std::ptrdiff_t next = 0;
      for (const auto& [begin, end] : b.ranges) {
        EXPECT_EQ(begin, next);
        EXPECT_LT(begin, end);  // no empty block
        next = end;
      }
      EXPECT_EQ(next, n);
    }
  }
  set_thread_count(before);
}

TEST(ParallelFor, BelowTheThresholdOneBlockOnTheCallingThread) {
  const int before = thread_count();
  set_thread_count(4);
  const Blocks b = blocks_of(100, 101);
  ASSERT_EQ(b.ranges.size(), 1u);
  EXPECT_EQ(b.ranges[0], std::make_pair(std::ptrdiff_t{0}, std::ptrdiff_t{100}));
  EXPECT_EQ(*b.threads.begin(), 0);
  EXPECT_FALSE(runs_threaded(100, 101));
  EXPECT_TRUE(runs_threaded(101, 101));
  EXPECT_TRUE(blocks_of(0, 0).ranges.empty());
  set_thread_count(before);
}

TEST(ParallelFor, ThreadCountBelowOneIsRefused) {
  EXPECT_THROW(set_thread_count(0), std::invalid_argument);
  EXPECT_GE(thread_count(), 1);
  EXPECT_GE(available_processors(), 1);
}

}  // namespace
}  // namespace drape
