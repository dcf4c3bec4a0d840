#include "core/dummy/nearest_particle_grid.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace drape::detail {

namespace {

// A denser grid than this many cells per point costs memory and row overhead without making
// the spans any shorter: the points lie on a surface, so most extra cells would be empty.
constexpr double kMaxCellsPerPoint = 16.0;

}  // namespace

ParticleGrid::ParticleGrid(const Eigen::VectorXd& positions, double cell_size) {
  assert(positions.size() % 3 == 0 && positions.size() > 0);
  assert(cell_size > 0.0 && std::isfinite(cell_size));
  const auto n = static_cast<int>(positions.size() / 3);
  const auto points = Eigen::Map<const Eigen::Matrix3Xd>(positions.data(), 3, n);
  m_lo = points.rowwise().minCoeff();
  m_hi = points.rowwise().maxCoeff();
  const Vec3 extent = m_hi - m_lo;

  // Raise the cell size until the cell count fits the budget (a thin or huge bounding box with
  // a small hint would otherwise allocate a dense grid of empty cells).
  const double max_cells = std::max(64.0, kMaxCellsPerPoint * n);
  // At least the smallest normal double: a hint that underflowed to 0 made 0 / 0 cells and the
  // loop below never ended.
  double cell = std::max(cell_size, std::numeric_limits<double>::min());
  for (;;) {
    const Vec3 dims = (extent / cell).array().floor() + 1.0;
    const double cells = dims.prod();
    if (cells <= max_cells) {
      for (int a = 0; a < 3; ++a) m_dims[a] = static_cast<int>(dims[a]);
      break;
    }
    cell *= std::cbrt(cells / max_cells) * 1.01;
  }
  m_cell = cell;
  m_inv_cell = 1.0 / cell;

  // Counting sort of the points by cell.
  const int num_cells = m_dims[0] * m_dims[1] * m_dims[2];
  std::vector<int> cell_of(n);
  m_cell_start.assign(num_cells + 1, 0);
  for (int i = 0; i < n; ++i) {
    const Vec3 q = points.col(i);
    cell_of[i] = cell_id(cell_coord(q.x(), 0), cell_coord(q.y(), 1), cell_coord(q.z(), 2));
    ++m_cell_start[cell_of[i] + 1];
  }
  for (int c = 0; c < num_cells; ++c) m_cell_start[c + 1] += m_cell_start[c];
  std::vector<int> fill(m_cell_start.begin(), m_cell_start.end() - 1);
  m_cell_particle.resize(n);
  m_cell_positions.resize(3 * static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    const int slot = fill[cell_of[i]]++;
    m_cell_particle[slot] = i;
    for (int a = 0; a < 3; ++a) m_cell_positions[3 * slot + a] = points(a, i);
  }
}

int ParticleGrid::cell_coord(double x, int axis) const {
  // Clamp in floating point before converting: far (or NaN) queries must not overflow an int.
  const double u = (x - m_lo[axis]) * m_inv_cell;
  if (!(u >= 0.0)) return 0;
  if (u >= m_dims[axis] - 1) return m_dims[axis] - 1;
  return static_cast<int>(u);
}

inline double ParticleGrid::row_gap_squared(const Vec3& p, int iy, int iz) const {
  const double y0 = m_lo.y() + iy * m_cell;
  const double z0 = m_lo.z() + iz * m_cell;
  const double gy = std::max(0.0, std::max(y0 - p.y(), p.y() - (y0 + m_cell)));
  const double gz = std::max(0.0, std::max(z0 - p.z(), p.z() - (z0 + m_cell)));
  return gy * gy + gz * gz;
}

inline GridHit ParticleGrid::scan_row(const Vec3& p, int ix0, int ix1, int iy, int iz,
                                      GridHit best) const {
  const int first = cell_id(ix0, iy, iz);
  const int end = m_cell_start[first + (ix1 - ix0) + 1];
  // Locals rather than writes through a reference, which the compiler would have to assume
  // alias the positions.
  int best_index = best.index;
  double best_d2 = best.distance_squared;
  const double* q = m_cell_positions.data() + 3 * static_cast<size_t>(m_cell_start[first]);
  for (int s = m_cell_start[first]; s < end; ++s, q += 3) {
    const double d2 = distance_squared(q, p);
    // Rarely taken, so well predicted; inside, a tie goes to the lower index (brute-force order).
    if (d2 <= best_d2 && (d2 < best_d2 || m_cell_particle[s] < best_index)) {
      best_d2 = d2;
      best_index = m_cell_particle[s];
    }
  }
  return {best_index, best_d2};
}

GridHit ParticleGrid::nearest_within(const Vec3& p, double radius) const {
  // Early out on the bounding box grown by the radius: the common case of a cloth particle
  // away from the dummy costs six comparisons.
  if (!(radius > 0.0) || p.x() + radius < m_lo.x() || p.x() - radius > m_hi.x() ||
      p.y() + radius < m_lo.y() || p.y() - radius > m_hi.y() || p.z() + radius < m_lo.z() ||
      p.z() - radius > m_hi.z())
    return {};
  const int x0 = cell_coord(p.x() - radius, 0), x1 = cell_coord(p.x() + radius, 0);
  const int y0 = cell_coord(p.y() - radius, 1), y1 = cell_coord(p.y() + radius, 1);
  const int z0 = cell_coord(p.z() - radius, 2), z1 = cell_coord(p.z() + radius, 2);
  GridHit best{-1, radius * radius};
  for (int iz = z0; iz <= z1; ++iz)
    for (int iy = y0; iy <= y1; ++iy)
      if (row_gap_squared(p, iy, iz) <= best.distance_squared)
        best = scan_row(p, x0, x1, iy, iz, best);
  return best.index < 0 ? GridHit{} : best;
}

GridHit ParticleGrid::nearest(const Vec3& p) const {
  const std::array<int, 3> c{cell_coord(p.x(), 0), cell_coord(p.y(), 1), cell_coord(p.z(), 2)};
  // Squared distance of p outside the bounding box along each axis: every unscanned point is at
  // least that far along the axes other than the one that separates it from the scanned block.
  Vec3 out2;
  for (int a = 0; a < 3; ++a) {
    const double o = std::max({0.0, m_lo[a] - p[a], p[a] - m_hi[a]});
    out2[a] = o * o;
  }
  const double total_out2 = out2.sum();

  // Chebyshev shells of cells around c: shell s holds the cells at exactly s cells from c.
  GridHit best{-1, std::numeric_limits<double>::infinity()};
  for (int s = 0;; ++s) {
    std::array<int, 3> b0{}, b1{};
    for (int a = 0; a < 3; ++a) {
      b0[a] = std::max(c[a] - s, 0);
      b1[a] = std::min(c[a] + s, m_dims[a] - 1);
    }
    for (int iz = b0[2]; iz <= b1[2]; ++iz)
      for (int iy = b0[1]; iy <= b1[1]; ++iy) {
        if (row_gap_squared(p, iy, iz) > best.distance_squared) continue;
        if (std::abs(iz - c[2]) == s || std::abs(iy - c[1]) == s) {
          best = scan_row(p, b0[0], b1[0], iy, iz, best);
        } else {  // inner row: only its two end cells belong to this shell
          if (c[0] - s >= 0) best = scan_row(p, c[0] - s, c[0] - s, iy, iz, best);
          if (s > 0 && c[0] + s < m_dims[0])
            best = scan_row(p, c[0] + s, c[0] + s, iy, iz, best);
        }
      }
    // Optimal once every unscanned cell is farther than the best: bound each face of the
    // scanned block that is not the grid's border (nothing lies beyond the border).
    double bound = std::numeric_limits<double>::infinity();
    bool unscanned = false;
    for (int a = 0; a < 3; ++a) {
      const double others = total_out2 - out2[a];
      if (b0[a] > 0) {
        unscanned = true;
        const double gap = p[a] - (m_lo[a] + b0[a] * m_cell);
        bound = std::min(bound, gap * gap + others);
      }
      if (b1[a] < m_dims[a] - 1) {
        unscanned = true;
        const double gap = m_lo[a] + (b1[a] + 1) * m_cell - p[a];
        bound = std::min(bound, gap * gap + others);
      }
    }
    if (!unscanned || best.distance_squared < bound) return best;
  }
}

}  // namespace drape::detail
