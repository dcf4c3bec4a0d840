// Fixed-block sums: one block is the one-thread loop itself, bit for bit; several blocks are
// their partial sums added in block order, the same bits on 1, 2 and 3 threads.
#include <gtest/gtest.h>

#include <array>

#include "core/parallel/fixed_block_sum.hpp"
#include "tests/support/test_support.hpp"

namespace drape {
namespace {

// Restores the thread count after a test.
class Threads {
 public:
  Threads() : m_before(thread_count()) {}
  ~Threads() { set_thread_count(m_before); }
  Threads(const Threads&) = delete;
  Threads& operator=(const Threads&) = delete;

 private:
  int m_before;
};

Eigen::VectorXd random_vector(Eigen::Index n, unsigned seed) {
  return testing::jitter(Eigen::VectorXd::Zero(n), 1.0, seed);
}

TEST(FixedBlockSum, OneBlockIsEigensOwnDotAndNorm) {
  const Threads restore;
  set_thread_count(2);
  for (const Eigen::Index n : {Eigen::Index{0}, Eigen::Index{1}, Eigen::Index{1200},
                               Eigen::Index{entries_per_block}}) {
    const Eigen::VectorXd a = random_vector(n, 1), b = random_vector(n, 2);
    EXPECT_EQ(block_dot(a, b), a.dot(b)) << n;
    EXPECT_EQ(block_norm(a), a.norm()) << n;
  }
}

TEST(FixedBlockSum, BlocksAddInBlockOrderOnAnyNumberOfThreads) {
  const Threads restore;
  const Eigen::Index n = 3 * entries_per_block + 5;  // four blocks, the last of 5 entries
  const Eigen::VectorXd a = random_vector(n, 3), b = random_vector(n, 4);
  double reference = 0.0;
  for (Eigen::Index start = 0; start < n; start += entries_per_block) {
    const Eigen::Index length = std::min<Eigen::Index>(entries_per_block, n - start);
    const double partial = a.segment(start, length).dot(b.segment(start, length));
    reference = start == 0 ? partial : reference + partial;
  }
  for (const int threads : {1, 2, 3}) {
    set_thread_count(threads);
    EXPECT_EQ(block_dot(a, b), reference) << threads << " threads";
    EXPECT_EQ(block_norm(a), std::sqrt(block_dot(a, a))) << threads << " threads";
  }
  EXPECT_NEAR(block_dot(a, b), a.dot(b), 1e-12 * a.norm() * b.norm());
}

TEST(FixedBlockSum, PartialsMayWriteTheirItemsAndReturnSeveralSums) {
  const Threads restore;
  const std::ptrdiff_t n = 5 * particles_per_block + 17;
  std::array<std::vector<double>, 3> written;
  std::array<std::array<double, 2>, 3> sums{};
  for (const int threads : {1, 2, 3}) {
    set_thread_count(threads);
    std::vector<double> out(static_cast<std::size_t>(n), -1.0);
    sums[static_cast<std::size_t>(threads - 1)] =
        fixed_block_sums<2>(n, particles_per_block, [&](std::ptrdiff_t begin, std::ptrdiff_t end) {
          std::array<double, 2> s{0.0, 0.0};
          for (std::ptrdiff_t i = begin; i < end; ++i) {
            out[static_cast<std::size_t>(i)] = 0.1 * static_cast<double>(i);
            s[0] += out[static_cast<std::size_t>(i)];
            s[1] += 1.0;
          }
          return s;
        });
    written[static_cast<std::size_t>(threads - 1)] = out;
  }
  // Every item written, the count exact, the sum the arithmetic series' up to round-off.
  EXPECT_EQ(sums[0][1], static_cast<double>(n));
  const double series = 0.1 * static_cast<double>(n) * static_cast<double>(n - 1) / 2.0;
  EXPECT_NEAR(sums[0][0], series, 1e-12 * series);
  for (std::size_t t = 1; t < 3; ++t) {
    EXPECT_EQ(sums[t], sums[0]);
    EXPECT_EQ(written[t], written[0]);
  }
  EXPECT_EQ(written[0][static_cast<std::size_t>(n - 1)], 0.1 * static_cast<double>(n - 1));
}

}  // namespace
}  // namespace drape
