#pragma once
// Uniform grid over the fixed object particles for exact nearest-particle queries. Compressed
// (CSR) layout: cells are numbered with x fastest, m_cell_start[c] .. m_cell_start[c + 1] are the
// particles of cell c, and m_cell_positions holds their positions in that same order. A row of
// cells along x is therefore one contiguous span of positions, so a query streams through a few
// short spans instead of chasing indices.
#include <array>
#include <vector>

#include "core/state/state.hpp"

namespace drape::detail {

/// Squared distance between the point at q[0..2] and p. The grid and the brute-force oracle share
/// it so that both see bit-identical distances and break ties the same way.
inline double distance_squared(const double* q, const Vec3& p) {
  const double dx = q[0] - p.x();
  const double dy = q[1] - p.y();
  const double dz = q[2] - p.z();
  return dx * dx + dy * dy + dz * dz;
}

/// A nearest particle found by the grid: its index and squared distance (-1: none).
struct GridHit {
  int index = -1;
  double distance_squared = 0.0;
};

/// Uniform CSR grid over a fixed set of points, answering exact nearest queries.
class ParticleGrid {
 public:
  ParticleGrid() = default;
  /// Builds the grid over interleaved xyz positions; `cell_size` > 0 is a hint that is raised
  /// when it would give more than about 16 cells per point.
  ParticleGrid(const Eigen::VectorXd& positions, double cell_size);

  double cell_size() const { return m_cell; }
  /// Number of cells along x, y and z.
  const std::array<int, 3>& dims() const { return m_dims; }

  /// Exact nearest point; ties go to the lowest index.
  GridHit nearest(const Vec3& p) const;
  /// Exact nearest point with distance < radius (ties to the lowest index), or index -1.
  GridHit nearest_within(const Vec3& p, double radius) const;
  /// Calls visit(index) for every point at distance < radius from p, in no particular order.
  template <class Visit>
  void for_each_within(const Vec3& p, double radius, Visit&& visit) const;

 private:
  int cell_coord(double x, int axis) const;
  int cell_id(int ix, int iy, int iz) const { return (iz * m_dims[1] + iy) * m_dims[0] + ix; }
  /// The better of `best` and the particles of cells ix0..ix1 of row (iy, iz).
  GridHit scan_row(const Vec3& p, int ix0, int ix1, int iy, int iz, GridHit best) const;
  /// Lower bound of the squared distance from p to the cells of row (iy, iz), ignoring x.
  double row_gap_squared(const Vec3& p, int iy, int iz) const;

  Vec3 m_lo = Vec3::Zero();  // lower corner of cell (0, 0, 0): the points' bounding box
  Vec3 m_hi = Vec3::Zero();  // upper corner of the points' bounding box
  double m_cell = 1.0;
  double m_inv_cell = 1.0;
  std::array<int, 3> m_dims{1, 1, 1};
  std::vector<int> m_cell_start;         // cells + 1 offsets into the two arrays below
  std::vector<int> m_cell_particle;      // particle indices sorted by cell
  std::vector<double> m_cell_positions;  // xyz of m_cell_particle, same order
};

template <class Visit>
void ParticleGrid::for_each_within(const Vec3& p, double radius, Visit&& visit) const {
  const double r2 = radius * radius;
  const int x0 = cell_coord(p.x() - radius, 0), x1 = cell_coord(p.x() + radius, 0);
  const int y0 = cell_coord(p.y() - radius, 1), y1 = cell_coord(p.y() + radius, 1);
  const int z0 = cell_coord(p.z() - radius, 2), z1 = cell_coord(p.z() + radius, 2);
  for (int iz = z0; iz <= z1; ++iz)
    for (int iy = y0; iy <= y1; ++iy) {
      const int first = cell_id(x0, iy, iz);
      const int end = m_cell_start[first + (x1 - x0) + 1];
      for (int s = m_cell_start[first]; s < end; ++s)
        if (distance_squared(&m_cell_positions[3 * static_cast<std::size_t>(s)], p) < r2)
          visit(m_cell_particle[s]);
    }
}

}  // namespace drape::detail
