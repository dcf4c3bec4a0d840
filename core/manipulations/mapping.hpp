#pragma once
// Mapping (paper section 3.3; docs/model.md section 7): the cloth laid onto the dummy along its centre line.
#include "core/cloth/cloth.hpp"
#include "core/dummy/dummy.hpp"

namespace drape {

/// Where mapping puts one cloth particle, with the quantities docs/model.md section 7 defines on the way.
struct MappedPoint {
  Vec3 position;
  double height;     ///< map_top - row * spacing
  double arc;        ///< col * spacing, walked along the polygon of the section above
  double angle;      ///< theta interpolated between the two bracketing object particles
  double radius;     ///< surface radius at (height, angle), before the threshold is added
};

/// Maps particle (row, col): row 0 to height map_top, row r to map_top - r*spacing; column c to
/// arc length c*spacing from the centre line (theta = 0), `direction` +1 towards +x, along the
/// polygon of the section just above that height; angle interpolated between the bracketing
/// object particles, radius between the bracketing sections, then extended by `threshold`.
/// A row beyond the girth keeps walking round the polygon.
MappedPoint map_particle(const Dummy& dummy, int row, int col, double spacing, double map_top,
                         int direction, double threshold);

/// Mapped positions of every cloth particle (3N, the cloth's ordering).
Eigen::VectorXd map_cloth(const Cloth& cloth, const Dummy& dummy, double map_top,
                          int direction, double threshold);

}  // namespace drape
