#pragma once
// Sums on threads with the same bits for any number of them (docs/performance/threads.md, "Sums
// over fixed blocks"): the items are cut into blocks of `reduction_block` whatever the thread
// count, each block is summed by one thread in the one-thread loop's order, and the blocks'
// sums are added on the calling thread in block order. A sum over one block is the one-thread
// loop itself, unchanged: every sum of a cloth of at most 2048 particles.
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

#include "core/parallel/parallel_for.hpp"

namespace drape {

/// Blocks of fixed-block sums: 2048 particles' worth (threaded_particles_from), so that a sum
/// runs on threads only where the loops beside it do: 2048 particles, their 6144 vector
/// entries, or 8192 springs (about four a particle; a 20 x 20 cloth has 2200 with bending).
inline constexpr std::ptrdiff_t particles_per_block = threaded_particles_from;
inline constexpr std::ptrdiff_t entries_per_block = 3 * particles_per_block;
inline constexpr std::ptrdiff_t springs_per_block = 4 * particles_per_block;

/// The K sums over [0, n) of `partial(begin, end)` (a std::array<double, K> of its items' sums,
/// which may also write its items' outputs), over fixed blocks of `block` items summed in block
/// order: the same bits for any thread count, and partial(0, n) itself when n fits one block.
template <std::size_t K, class Partial>
std::array<double, K> fixed_block_sums(std::ptrdiff_t n, std::ptrdiff_t block,
                                       Partial&& partial) {
  const std::ptrdiff_t blocks = (n + block - 1) / block;
  if (blocks <= 1) return partial(std::ptrdiff_t{0}, n);
  std::vector<std::array<double, K>> sums(static_cast<std::size_t>(blocks));
  parallel_for(blocks, 2, [&](std::ptrdiff_t first, std::ptrdiff_t last) {
    for (std::ptrdiff_t b = first; b < last; ++b)
      sums[static_cast<std::size_t>(b)] = partial(b * block, std::min(n, (b + 1) * block));
  });
  std::array<double, K> total = sums.front();
  for (std::size_t b = 1; b < sums.size(); ++b)
    for (std::size_t k = 0; k < K; ++k) total[k] += sums[b][k];
  return total;
}

/// One fixed-block sum: fixed_block_sums<1>.
template <class Partial>
double fixed_block_sum(std::ptrdiff_t n, std::ptrdiff_t block, Partial&& partial) {
  return fixed_block_sums<1>(n, block, [&](std::ptrdiff_t begin, std::ptrdiff_t end) {
    return std::array<double, 1>{partial(begin, end)};
  })[0];
}

/// a . b as a fixed-block sum (Eigen's dot on each block; a.dot(b) itself on one block).
inline double block_dot(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return fixed_block_sum(a.size(), entries_per_block,
                         [&](std::ptrdiff_t begin, std::ptrdiff_t end) {
                           return a.segment(begin, end - begin).dot(b.segment(begin, end - begin));
                         });
}

/// |a| as a fixed-block sum of squares (a.norm() itself on one block).
inline double block_norm(const Eigen::VectorXd& a) {
  return std::sqrt(
      fixed_block_sum(a.size(), entries_per_block, [&](std::ptrdiff_t begin, std::ptrdiff_t end) {
        return a.segment(begin, end - begin).squaredNorm();
      }));
}

}  // namespace drape
