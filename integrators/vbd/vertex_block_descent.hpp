#pragma once
// One Gauss-Seidel sweep of Vertex Block Descent (Chen, Liu, Yang and Yuksel 2024, ACM TOG
// 43(4), algorithm 1): for each colour of colour_particles, for each free particle i of it, the
// Newton step dx = H_i^-1 f_i of G's block on i (vertex_block_potential.hpp), halved until G
// does not rise (at most max_halvings times, else the particle stays). Particles of one colour
// share no spring, so the order within a colour does not change the result: a colour's
// particles run on the hot loops' threads (core/parallel).
#include <Eigen/Core>

#include "integrators/colouring/graph_colouring.hpp"
#include "integrators/vbd/vertex_block_potential.hpp"

namespace drape {

/// Block Gauss-Seidel on backward Euler's incremental potential.
class VertexBlockDescent {
 public:
  explicit VertexBlockDescent(const ClothSystem& system);

  /// Starts a step of size h from x_n, v_n (3N each).
  void begin_step(double h, ConstVecRef x_n, ConstVecRef v_n) {
    m_potential.begin_step(h, x_n, v_n);
  }
  /// One sweep from x (3N, fixed particles already in place), in place. Freezes the spring
  /// damping directions at x first, so that the sweep descends on one function. Returns the
  /// number of step halvings.
  long sweep(VecRef x);
  const VertexBlockPotential& potential() const { return m_potential; }
  VertexBlockPotential& potential() { return m_potential; }

 private:
  const ClothSystem& m_system;
  VertexBlockPotential m_potential;
  std::vector<std::vector<int>> m_colours;  // the particles, colour by colour (fixed ones skipped)
};

}  // namespace drape
