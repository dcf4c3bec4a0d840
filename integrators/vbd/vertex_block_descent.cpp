#include "integrators/vbd/vertex_block_descent.hpp"

#include <Eigen/Cholesky>
#include <atomic>
#include <limits>

#include "core/parallel/parallel_for.hpp"

namespace drape {

namespace {

// A block's Newton step overshoots where G's curvature grows along it (a particle entering
// contact, a spring stretched transversally); ten halvings shrink it to 1e-3 of its length.
constexpr int max_halvings = 10;
// A change within 1e3 epsilon of its terms' magnitude is round-off: taken as no rise. Without
// this, converged particles had every step rejected after ten halvings each (ten times the
// cost of a sweep, and the iterates stalled at the noise instead of settling on it).
constexpr double round_off = 1e3 * std::numeric_limits<double>::epsilon();

// Whether moving particle i by dx does not raise G (to round-off).
bool descends(const VertexBlockPotential& potential, int i, const double* x, const Vec3& dx) {
  double magnitude = 0.0;
  return potential.energy_change(i, x, dx, magnitude) <= round_off * magnitude;
}

}  // namespace

VertexBlockDescent::VertexBlockDescent(const ClothSystem& system)
    : m_system(system),
      m_potential(system),
      m_colours(colour_particles(system.num_particles(), system.cloth().springs)) {}

long VertexBlockDescent::sweep(VecRef x) {
  m_potential.freeze_directions(x);
  const auto& fixed = m_system.constraints().mask();
  double* positions = x.data();
  // A count, added up exactly in any order.
  std::atomic<long> halvings{0};
  for (const std::vector<int>& colour : m_colours) {
    // The particles of one colour share no spring: each block reads only other colours'
    // positions, so the colour's particles move on threads with the same bits.
    parallel_for(static_cast<std::ptrdiff_t>(colour.size()), threaded_particles_from,
                 [&](std::ptrdiff_t begin, std::ptrdiff_t end) {
      long block_halvings = 0;
      for (std::ptrdiff_t p = begin; p < end; ++p) {
        const int i = colour[static_cast<std::size_t>(p)];
        if (fixed[static_cast<std::size_t>(i)]) continue;
        const VertexBlock b = m_potential.block(i, positions, true);
        // H_i >= M / h^2 > 0 (definite block): Cholesky always succeeds.
        Vec3 dx = b.hessian.llt().solve(b.force);
        int k = 0;
        while (!descends(m_potential, i, positions, dx)) {
          if (++k > max_halvings) break;
          dx *= 0.5;
        }
        block_halvings += k;
        if (k > max_halvings) continue;
        for (int a = 0; a < 3; ++a) positions[3 * i + a] += dx[a];
      }
      halvings += block_halvings;
    });
  }
  return halvings;
}

}  // namespace drape
