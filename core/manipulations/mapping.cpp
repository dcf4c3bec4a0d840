#include "core/manipulations/mapping.hpp"

#include <cmath>

namespace drape {

namespace {

// Index of the section just above `height` (y_k >= height > y_k+1); clamped to the stack.
int section_above(const DummySections& s, double height) {
  int k = 0;
  while (k + 1 < s.num_sections() && s.y[k + 1] >= height) ++k;
  return k;
}

Eigen::Vector2d polygon_vertex(const DummySections& s, const Dummy& dummy, int k, int j) {
  const int points = s.points();
  const int jj = ((j % points) + points) % points;
  const double theta = dummy.angle(jj);
  const double r = s.radius(k, jj);
  return {s.cx[k] + r * std::sin(theta), s.cz[k] + r * std::cos(theta)};
}

}  // namespace

MappedPoint map_particle(const Dummy& dummy, int row, int col, double spacing, double map_top,
                         int direction, double threshold) {
  const DummySections& s = dummy.sections();
  MappedPoint m;
  m.height = map_top - row * spacing;
  m.arc = col * spacing;
  const int k = section_above(s, m.height);
  const double step = 2.0 * M_PI / s.points();

  // Walk the section's polygon from the centre line until the arc length is used up.
  double walked = 0.0;
  int edge = 0;
  double fraction = 0.0;
  while (true) {
    const Eigen::Vector2d a = polygon_vertex(s, dummy, k, direction * edge);
    const Eigen::Vector2d b = polygon_vertex(s, dummy, k, direction * (edge + 1));
    const double length = (b - a).norm();
    if (walked + length >= m.arc || length <= 0.0) {
      fraction = length > 0.0 ? (m.arc - walked) / length : 0.0;
      break;
    }
    walked += length;
    ++edge;
  }
  m.angle = direction * (edge + fraction) * step;
  m.radius = dummy.surface_radius(m.height, m.angle);
  const Eigen::Vector2d axis = dummy.axis_at(m.height);
  const double r = m.radius + threshold;
  m.position = Vec3(axis.x() + r * std::sin(m.angle), m.height, axis.y() + r * std::cos(m.angle));
  return m;
}

Eigen::VectorXd map_cloth(const Cloth& cloth, const Dummy& dummy, double map_top, int direction,
                          double threshold) {
  Eigen::VectorXd x(3 * cloth.size());
  for (int i = 0; i < cloth.size(); ++i)
    x.segment<3>(3 * i) = map_particle(dummy, cloth.row_of(i), cloth.col_of(i),
                                       cloth.params.spacing, map_top, direction, threshold)
                              .position;
  return x;
}

}  // namespace drape
