#pragma once
// The springs of a cloth's stencils (spring_stencil.hpp) listed one by one, for the loops that
// visit springs singly: Jacobians, energies and the integrators' per-spring work. A view: it is
// built from the stencils by list_springs alone and holds nothing they do not.
#include <Eigen/Core>
#include <vector>

#include "core/cloth/spring_stencil.hpp"

namespace drape {

/// Flat arrays, one entry per spring, in list_springs' order.
struct SpringList {
  Eigen::ArrayXi first;      ///< particle i
  Eigen::ArrayXi second;     ///< particle j = i + the stencil's offset
  Eigen::ArrayXd rest;       ///< the stencil's rest length L0
  Eigen::ArrayXd stiffness;  ///< the stencil's k

  Eigen::Index size() const { return first.size(); }
};

/// The springs of `stencils` on a rows x cols grid, stencil by stencil. Within a stencil they
/// come in two colour classes, each a matching of the grid (no two springs of a class share a
/// particle), each row by row and column by column: loops that scatter per spring (Jacobian
/// products, assembly) then have no read-after-write chains between neighbouring springs, and
/// each class sweeps the grid in memory order. A spring's class is the parity of its start's
/// row (column, along rows) divided by the offset's length along that axis: springs of one
/// stencil that share a particle start exactly that length apart.
SpringList list_springs(const std::vector<SpringStencil>& stencils, int rows, int cols);

}  // namespace drape
