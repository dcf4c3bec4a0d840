#pragma once
// The mesh dummy source of docs/model.md section 3: a closed surface mesh (an OBJ file) sliced by horizontal
// planes, each slice turned into a section by casting `points` rays from its centre and taking
// the nearest surface hit along each. Format, centre and defaults: docs/dress_form.md.
#include <Eigen/Core>
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "core/dummy/dummy.hpp"

namespace drape {

/// A triangle surface in metres, with the name of the file it came from for error messages.
struct TriangleMesh {
  std::string file;                           ///< source file, named in errors
  std::vector<Vec3> vertices;                 ///< metres
  std::vector<std::array<int, 3>> triangles;  ///< vertex indices (polygons fanned, convex)
};

/// A vertical interval, in metres.
struct HeightRange {
  double top = 0.0;
  double bottom = 0.0;
};

/// One closed contour of a slice: its corners in the (x, z) plane, the last joined to the first.
using SliceContour = std::vector<Eigen::Vector2d>;

/// Reads an OBJ file, multiplying coordinates by `unit` (metres per OBJ unit) and fanning each
/// (convex) polygon from its first corner. A missing or unparsable file, a bad vertex index or
/// a mesh without faces throws InputError naming it.
TriangleMesh read_obj_mesh(const std::string& file, double unit);

/// Highest and lowest vertex height of a mesh.
HeightRange vertical_extent(const TriangleMesh& mesh);

/// The contours where the plane at height y cuts the mesh (empty when it misses the mesh).
std::vector<SliceContour> slice_mesh(const TriangleMesh& mesh, double y);

/// Section centre (cx, cz) of a slice: cx of the area centroid of its largest contour, cz
/// midway between the front and back surface hits of the line x = cx through that centroid.
/// Empty when the slice has no contour with an area or that line misses the surface.
std::optional<Eigen::Vector2d> slice_centre(const std::vector<SliceContour>& contours);

/// Distance from `centre` to the nearest crossing of the ray at angle theta (from +z towards +x)
/// with any contour, or a negative value when the ray crosses none.
double nearest_ray_hit(const std::vector<SliceContour>& contours,
                       const Eigen::Vector2d& centre, double theta);

/// Slices the mesh at `sections` heights evenly spaced from y_top to y_bottom (both included)
/// into `points` rays each. A height without surface or a ray that hits nothing throws
/// InputError naming the mesh file, the height and the angle.
DummySections mesh_sections(const TriangleMesh& mesh, double y_top, double y_bottom,
                            int sections, int points);

/// Default slicing range: the mesh's vertical extent less half a section spacing at each end,
/// so that the sections are cell-centred (like the sphere's) and no end slice grazes a tip.
HeightRange default_slice_range(const TriangleMesh& mesh, int sections);

}  // namespace drape
