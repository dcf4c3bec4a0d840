#pragma once
// Colourings of the spring graph for the Gauss-Seidel sweeps of XPBD and VBD: within one colour
// no two members touch, so a colour can be swept in any order, or in parallel, with the same
// result. Greedy in index order (each member takes the smallest colour its neighbours left), so
// the colouring, and every sweep over it, is deterministic.
#include <vector>

#include "core/cloth/spring_list.hpp"

namespace drape {

/// Members (particle or spring indices) of each colour, ascending within a colour.
using Colouring = std::vector<std::vector<int>>;

/// Particles coloured so that no spring joins two particles of one colour.
Colouring colour_particles(int num_particles, const SpringList& springs);
/// Springs coloured so that no two springs of one colour share a particle.
Colouring colour_springs(int num_particles, const SpringList& springs);

}  // namespace drape
