#include "core/dummy/mesh_sections.hpp"

#include <fmt/format.h>
#include <tiny_obj_loader.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <unordered_map>

#include "core/io/input_error.hpp"
#include "core/io/json_reader.hpp"
#include "core/io/scene_limits.hpp"

namespace drape {

namespace {

constexpr double kPi = 3.141592653589793238462643383279;

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

/// Signed area of a contour (shoelace) and its area centroid.
struct ContourArea {
  double area = 0.0;
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
};

ContourArea contour_area(const SliceContour& contour) {
  ContourArea out;
  Eigen::Vector2d moment = Eigen::Vector2d::Zero();
  for (size_t i = 0; i < contour.size(); ++i) {
    const Eigen::Vector2d& p = contour[i];
    const Eigen::Vector2d& q = contour[(i + 1) % contour.size()];
    const double c = cross(p, q);
    out.area += 0.5 * c;
    moment += (p + q) * c / 6.0;
  }
  if (out.area != 0.0) out.centroid = moment / out.area;
  return out;
}

/// Cut segments of one slice, as indices into their cut points.
struct SliceSegments {
  std::vector<Eigen::Vector2d> points;
  std::vector<std::array<int, 2>> segments;
};

SliceSegments cut_triangles(const TriangleMesh& mesh, double y) {
  // A cut point is keyed by the mesh edge it lies on and computed from the edge's vertices in
  // index order, so the two triangles sharing an edge yield the same point bit for bit and the
  // contours chain without a tolerance. A vertex exactly at y counts as above the plane: every
  // triangle then has zero or two cut edges, even when the plane passes through vertices.
  SliceSegments out;
  std::unordered_map<std::uint64_t, int> point_of_edge;
  auto cut_point = [&](int a, int b) {
    if (a > b) std::swap(a, b);
    const std::uint64_t key = static_cast<std::uint64_t>(a) << 32 | static_cast<std::uint32_t>(b);
    const auto [it, inserted] = point_of_edge.emplace(key, static_cast<int>(out.points.size()));
    if (inserted) {
      const Vec3& va = mesh.vertices[a];
      const Vec3& vb = mesh.vertices[b];
      const double s = (y - va.y()) / (vb.y() - va.y());  // the sides differ: vb.y() != va.y()
      out.points.emplace_back(va.x() + s * (vb.x() - va.x()), va.z() + s * (vb.z() - va.z()));
    }
    return it->second;
  };
  for (const auto& triangle : mesh.triangles) {
    std::array<int, 2> segment{};
    int cuts = 0;
    for (int e = 0; e < 3; ++e) {
      const int a = triangle[e];
      const int b = triangle[(e + 1) % 3];
      if ((mesh.vertices[a].y() >= y) != (mesh.vertices[b].y() >= y))
        segment[cuts++] = cut_point(a, b);
    }
    if (cuts == 2) out.segments.push_back(segment);
  }
  return out;
}

// The OBJ file's text without a UTF-8 byte order mark, which Windows editors put before text and
// tinyobjloader does not skip: left in, it hid the first line's tag, so that line's vertex was
// dropped and every face index after it pointed at the next vertex (docs/scene.md).
std::string obj_text(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file, "", "cannot open file");
  std::ostringstream text;
  text << in.rdbuf();
  std::string out = std::move(text).str();
  constexpr std::string_view bom = "\xEF\xBB\xBF";
  if (std::string_view(out).substr(0, bom.size()) == bom) out.erase(0, bom.size());
  return out;
}

// tinyobjloader reads a coordinate it cannot parse ("nan", "inf", "1e999") as 0, a missing one
// as 0, and an index beyond int's range as a wrapped number, without a word, and drops faces of
// fewer than three corners: every vertex and face line is checked here first, naming its line.
// Coordinates are bounded as a scene's are (docs/scene.md, Limits), in metres once scaled by
// `unit`.
void check_lines(const std::string& file, const std::string& text, double unit) {
  std::istringstream in(text);
  std::string line;
  long vertices = 0;
  for (long number = 1; std::getline(in, line); ++number) {
    std::istringstream fields(line);
    std::string tag, token;
    if (!(fields >> tag) || (tag != "v" && tag != "f")) continue;
    const auto error = [&](const std::string& message) {
      return InputError(file, "line " + std::to_string(number), message);
    };
    if (tag == "v") {
      ++vertices;
      int coordinates = 0;
      for (; coordinates < 3 && fields >> token; ++coordinates) {
        double x = 0.0;
        const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), x);
        if (ec != std::errc() || end != token.data() + token.size() || !std::isfinite(x))
          throw error("vertex coordinate \"" + token + "\" is not a finite number");
        if (!(std::abs(unit * x) <= limits::max_coordinate))
          throw error(fmt::format("vertex coordinate {} x unit {:g} m is beyond +-{:g} m", token,
                                  unit, limits::max_coordinate));
      }
      if (coordinates < 3)
        throw error(fmt::format("a vertex of {} coordinates (x y z needed)", coordinates));
      continue;
    }
    int corners = 0;
    for (; fields >> token; ++corners) {
      // v, v/vt, v//vn or v/vt/vn: the vertex is the first number, negative counting back.
      long index = 0;
      const std::string_view vertex(token.data(), std::min(token.find('/'), token.size()));
      const auto [end, ec] = std::from_chars(vertex.data(), vertex.data() + vertex.size(), index);
      if (ec != std::errc() || end != vertex.data() + vertex.size() || index == 0 ||
          index < -vertices || index > vertices)
        throw error(fmt::format("face corner \"{}\" is not a vertex of the {} before it", token,
                                vertices));
    }
    if (corners < 3) throw error(fmt::format("a face of {} corners (at least 3)", corners));
  }
}

}  // namespace

TriangleMesh read_obj_mesh(const std::string& file, double unit) {
  // A directory or a device (/dev/zero) is said to be one (docs/scene.md, Limits).
  if (const auto reason = unreadable_file_reason(file)) throw InputError(file, "", *reason);
  const std::string text = obj_text(file);
  check_lines(file, text, unit);
  tinyobj::ObjReaderConfig config;
  // Polygons are fanned from their first corner below rather than split along their shorter
  // diagonal by tinyobjloader: that is how the reference slicing of the built-in body split
  // its quads (0.1 mm agreement instead of 9 mm in the crotch notch, where rays graze).
  config.triangulate = false;
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  // Materials carry no geometry: none is read (an `mtllib` line finds an empty library).
  if (!reader.ParseFromString(text, "", config)) {
    std::string why = reader.Error();
    while (!why.empty() && std::isspace(static_cast<unsigned char>(why.back()))) why.pop_back();
    throw InputError(file, "", "not a valid OBJ file: " + why);
  }

  TriangleMesh mesh;
  mesh.file = file;
  const std::vector<tinyobj::real_t>& coordinates = reader.GetAttrib().vertices;
  for (size_t i = 0; i + 2 < coordinates.size(); i += 3) {
    const Vec3 v(coordinates[i], coordinates[i + 1], coordinates[i + 2]);
    mesh.vertices.push_back(unit * v);
  }
  const int num_vertices = static_cast<int>(mesh.vertices.size());
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    size_t first = 0;
    for (const unsigned int corners : shape.mesh.num_face_vertices) {
      std::vector<int> face;
      for (size_t c = first; c < first + corners; ++c) {
        const int v = shape.mesh.indices[c].vertex_index;
        // check_lines has checked the file's indices; this guards the reads below against a
        // reading of them by tinyobjloader that would differ.
        if (v < 0 || v >= num_vertices)
          throw InputError(file, "", fmt::format("a face refers to vertex {} of {}", v + 1,
                                                 num_vertices));
        face.push_back(v);
      }
      for (size_t c = 1; c + 1 < face.size(); ++c)
        mesh.triangles.push_back({face[0], face[c], face[c + 1]});
      first += corners;
    }
  }
  if (mesh.triangles.empty()) throw InputError(file, "", "the OBJ file has no faces");
  return mesh;
}

HeightRange vertical_extent(const TriangleMesh& mesh) {
  HeightRange out{-std::numeric_limits<double>::infinity(),
                  std::numeric_limits<double>::infinity()};
  for (const Vec3& v : mesh.vertices) {
    out.top = std::max(out.top, v.y());
    out.bottom = std::min(out.bottom, v.y());
  }
  return out;
}

HeightRange default_slice_range(const TriangleMesh& mesh, int sections) {
  const HeightRange extent = vertical_extent(mesh);
  const double margin = 0.5 * (extent.top - extent.bottom) / sections;
  return {extent.top - margin, extent.bottom + margin};
}

std::vector<SliceContour> slice_mesh(const TriangleMesh& mesh, double y) {
  const SliceSegments cut = cut_triangles(mesh, y);
  std::vector<std::vector<int>> incident(cut.points.size());
  for (size_t s = 0; s < cut.segments.size(); ++s)
    for (int p : cut.segments[s]) incident[p].push_back(static_cast<int>(s));

  // Walks start at the loose ends of open chains (a mesh with holes) before the closed loops,
  // so that an open chain comes out whole; the contour then closes it with a straight chord.
  std::vector<int> starts;
  for (size_t p = 0; p < incident.size(); ++p)
    if (incident[p].size() == 1) starts.push_back(static_cast<int>(p));
  for (const auto& segment : cut.segments) starts.push_back(segment[0]);

  std::vector<bool> used(cut.segments.size(), false);
  auto unused_segment_at = [&](int p) {
    for (int s : incident[p])
      if (!used[s]) return s;
    return -1;
  };
  std::vector<SliceContour> contours;
  for (int start : starts) {
    int p = start;
    int s = unused_segment_at(p);
    if (s < 0) continue;
    SliceContour contour;
    while (s >= 0) {
      used[s] = true;
      contour.push_back(cut.points[p]);
      p = cut.segments[s][0] == p ? cut.segments[s][1] : cut.segments[s][0];
      s = unused_segment_at(p);
    }
    if (p != start) contour.push_back(cut.points[p]);  // the far end of an open chain
    contours.push_back(std::move(contour));
  }
  return contours;
}

std::optional<Eigen::Vector2d> slice_centre(const std::vector<SliceContour>& contours) {
  ContourArea largest;
  for (const SliceContour& contour : contours) {
    const ContourArea candidate = contour_area(contour);
    if (std::abs(candidate.area) > std::abs(largest.area)) largest = candidate;
  }
  if (largest.area == 0.0) return std::nullopt;
  // The front and back rays (theta = 0 and pi) then have equal length, as in the reference
  // slicing of the built-in body (its CSV has r000 = r180 on every row). The area centroid
  // alone sits up to 1 cm behind that midpoint on the torso.
  const double front = nearest_ray_hit(contours, largest.centroid, 0.0);
  const double back = nearest_ray_hit(contours, largest.centroid, kPi);
  if (front < 0.0 || back < 0.0) return std::nullopt;
  return Eigen::Vector2d(largest.centroid.x(), largest.centroid.y() + 0.5 * (front - back));
}

double nearest_ray_hit(const std::vector<SliceContour>& contours,
                       const Eigen::Vector2d& centre, double theta) {
  const Eigen::Vector2d direction(std::sin(theta), std::cos(theta));  // (x, z)
  double nearest = std::numeric_limits<double>::infinity();
  for (const SliceContour& contour : contours) {
    for (size_t i = 0; i < contour.size(); ++i) {
      const Eigen::Vector2d& a = contour[i];
      const Eigen::Vector2d edge = contour[(i + 1) % contour.size()] - a;
      // centre + t direction = a + s edge. An edge parallel to the ray (denominator 0) can only
      // be touched at its ends, which its neighbours report.
      const double denominator = cross(direction, edge);
      if (denominator == 0.0) continue;
      const Eigen::Vector2d w = a - centre;
      const double t = cross(w, edge) / denominator;
      const double s = cross(w, direction) / denominator;
      if (t > 0.0 && s >= 0.0 && s <= 1.0) nearest = std::min(nearest, t);
    }
  }
  return std::isfinite(nearest) ? nearest : -1.0;
}

DummySections mesh_sections(const TriangleMesh& mesh, double y_top, double y_bottom,
                            int sections, int points) {
  DummySections out;
  out.radius.resize(sections, points);
  for (int k = 0; k < sections; ++k) {
    // The last height is set exactly: the formula may round past y_bottom.
    const double y =
        k + 1 == sections ? y_bottom : y_top - k * (y_top - y_bottom) / (sections - 1);
    const std::vector<SliceContour> contours = slice_mesh(mesh, y);
    const std::optional<Eigen::Vector2d> centre = slice_centre(contours);
    if (!centre)
      throw InputError(mesh.file, "", fmt::format("section {} at y = {:.6g} m: no surface "
                                                  "encloses a centre",
                                                  k, y));
    for (int j = 0; j < points; ++j) {
      const double theta = 2.0 * kPi * j / points;
      const double radius = nearest_ray_hit(contours, *centre, theta);
      if (radius < 0.0)
        throw InputError(mesh.file, "",
                         fmt::format("section {} at y = {:.6g} m: the ray at theta = {:.6g} deg "
                                     "from the centre ({:.6g}, {:.6g}) hits no surface",
                                     k, y, theta * 180.0 / kPi, centre->x(), centre->y()));
      out.radius(k, j) = radius;
    }
    out.y.push_back(y);
    out.cx.push_back(centre->x());
    out.cz.push_back(centre->y());
  }
  return out;
}

}  // namespace drape
