#include "core/dummy/dummy_sources.hpp"

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <utility>

#include "core/dummy/dress_form.hpp"
#include "core/io/json_reader.hpp"
#include "core/io/scene_limits.hpp"
#include "core/dummy/mesh_sections.hpp"

namespace drape {

namespace {

constexpr double kPi = 3.141592653589793238462643383279;
// Far beyond any useful dummy (the paper's has 2560 particles); guards against typos that would
// allocate gigabytes.
constexpr std::int64_t kMaxDummyParticles = 10'000'000;

struct Resolution {
  int sections = kDefaultDummySections;
  int points = kDefaultDummyPoints;
};

/// Where relative paths of a source resolve.
struct SourceContext {
  std::filesystem::path base_dir;

  std::filesystem::path resolve(const std::filesystem::path& name) const {
    return name.is_absolute() ? name : base_dir / name;
  }
};

using SourceReader = DummySections (*)(JsonReader&, const std::string& key, const Resolution&,
                                       const SourceContext&);
using BuiltinReader = DummySections (*)(JsonReader&, const Resolution&);

// Radii and heights beyond docs/scene.md's Limits would overflow the model's products.
double radius_of(JsonReader& reader) {
  return reader.at_most("radius", reader.positive("radius", reader.number("radius")),
                        limits::max_length);
}

void require_above(const JsonReader& reader, double y_top, double y_bottom) {
  reader.within("y_top", y_top, limits::max_coordinate);
  reader.within("y_bottom", y_bottom, limits::max_coordinate);
  if (!(y_top > y_bottom))
    throw reader.error("y_top", "must be above y_bottom (" + nlohmann::json(y_top).dump() +
                                    " <= " + nlohmann::json(y_bottom).dump() + ")");
}

DummySections read_dress_form(JsonReader&, const Resolution& res) {
  return dress_form_sections(res.sections, res.points);
}

DummySections read_cylinder(JsonReader& reader, const Resolution& res) {
  const double radius = radius_of(reader);
  const std::vector<double> center = reader.has("center") ? reader.numbers("center")
                                                          : std::vector<double>{0.0, 0.0};
  if (center.size() != 2) throw reader.error("center", "expected 2 numbers [cx, cz]");
  const double y_top = reader.number("y_top");
  const double y_bottom = reader.number("y_bottom");
  require_above(reader, y_top, y_bottom);
  return cylinder_sections(radius, center[0], center[1], y_top, y_bottom, res.sections,
                           res.points);
}

DummySections read_sphere(JsonReader& reader, const Resolution& res) {
  const double radius = radius_of(reader);
  const Vec3 center = reader.vec3("center", Vec3::Zero());
  reader.within("center", center, limits::max_coordinate);
  return sphere_sections(radius, center, res.sections, res.points);
}

// The `builtin` names.
constexpr std::pair<const char*, BuiltinReader> kBuiltins[] = {
    {"dress-form", read_dress_form},
    {"cylinder", read_cylinder},
    {"sphere", read_sphere},
};

DummySections read_builtin(JsonReader& reader, const std::string& key, const Resolution& res,
                           const SourceContext&) {
  const std::string name = reader.string(key);
  std::string names;
  for (const auto& [builtin, read] : kBuiltins) {
    if (name == builtin) return read(reader, res);
    names += std::string(names.empty() ? "" : ", ") + builtin;
  }
  throw reader.error(key, "unknown built-in dummy '" + name + "' (known: " + names + ")");
}

DummySections read_file_source(JsonReader& reader, const std::string& key,
                               const Resolution& res, const SourceContext& context) {
  const std::filesystem::path path = context.resolve(reader.string(key));
  // The scene's field names the problem first; the sections file's own field follows.
  try {
    return resample_sections(read_sections_file(path.string()), res.sections, res.points);
  } catch (const InputError& e) {
    throw reader.error(key, e.what());
  }
}

DummySections read_mesh_source(JsonReader& reader, const std::string& key,
                               const Resolution& res, const SourceContext& context) {
  const double unit =
      reader.at_least("unit", reader.at_most("unit", reader.number("unit", 1.0), 1e3), 1e-6);
  const std::filesystem::path path = context.resolve(reader.string(key));
  // As for sections files: the scene's field first, then the mesh file's own message.
  TriangleMesh mesh;
  try {
    mesh = read_obj_mesh(path.string(), unit);
  } catch (const InputError& e) {
    throw reader.error(key, e.what());
  }
  // A flat mesh has no heights to slice between: said of the file, not of the y_top and
  // y_bottom it would have given.
  const HeightRange extent = vertical_extent(mesh);
  if (!(extent.top > extent.bottom))
    throw reader.error(key, InputError(path.string(), "",
                                       "the mesh has no height: every vertex at y = " +
                                           nlohmann::json(extent.top).dump() + " m after unit")
                                .what());
  const HeightRange fallback = default_slice_range(mesh, res.sections);
  const double y_top = reader.number("y_top", fallback.top);
  const double y_bottom = reader.number("y_bottom", fallback.bottom);
  require_above(reader, y_top, y_bottom);
  // A plane at or beyond the mesh's extent cuts nothing or only a tip: name the field, not the
  // first empty slice.
  if (!(y_top < extent.top))
    throw reader.error("y_top", "must be below the mesh's top (" +
                                    nlohmann::json(extent.top).dump() + " m after unit)");
  if (!(y_bottom > extent.bottom))
    throw reader.error("y_bottom", "must be above the mesh's bottom (" +
                                       nlohmann::json(extent.bottom).dump() + " m after unit)");
  try {
    return mesh_sections(mesh, y_top, y_bottom, res.sections, res.points);
  } catch (const InputError& e) {
    throw reader.error(key, e.what());
  }
}

// The keys that select a source; the default (no key) is the dress form.
constexpr std::pair<const char*, SourceReader> kSources[] = {
    {"builtin", read_builtin},
    {"file", read_file_source},
    {"mesh", read_mesh_source},
};

int read_count(JsonReader& reader, const std::string& key, int fallback, int minimum) {
  const int value = reader.integer(key, fallback);
  if (value < minimum)
    throw reader.error(key, "must be at least " + std::to_string(minimum) + ", got " +
                                std::to_string(value));
  return value;
}

}  // namespace

DummySections make_dummy_sections(const nlohmann::json& spec, const std::string& file,
                                  const std::string& path,
                                  const std::filesystem::path& base_dir) {
  JsonReader reader(spec, file, path);
  Resolution res;
  res.sections = read_count(reader, "sections", kDefaultDummySections, 2);
  res.points = read_count(reader, "points", kDefaultDummyPoints, 3);
  if (static_cast<std::int64_t>(res.sections) * res.points > kMaxDummyParticles)
    throw reader.error("sections", "sections x points exceeds " +
                                       std::to_string(kMaxDummyParticles) + " particles");
  // Bounded below too: a body scaled to nothing has no spacing for its nearest-particle grid
  // (1e-300 made its cells underflow) and no sections to tell apart (docs/scene.md, Limits).
  const double scale = reader.at_least(
      "scale", reader.at_most("scale", reader.number("scale", 1.0), 1e3), 1e-3);
  const Vec3 offset = reader.vec3("offset", Vec3::Zero());
  reader.within("offset", offset, limits::max_coordinate);

  const std::pair<const char*, SourceReader>* source = nullptr;
  for (const auto& candidate : kSources) {
    if (!reader.has(candidate.first)) continue;
    if (source)
      throw reader.error(candidate.first, std::string("conflicts with ") +
                                              reader.field(source->first) +
                                              ": give one dummy source");
    source = &candidate;
  }
  DummySections sections = source
                                ? source->second(reader, source->first, res, {base_dir})
                                : dress_form_sections(res.sections, res.points);
  reader.finish();
  place_sections(sections, scale, offset);
  return sections;
}

std::vector<std::pair<std::string, std::filesystem::path>> dummy_file_paths(
    const nlohmann::json& spec, const std::filesystem::path& base_dir) {
  std::vector<std::pair<std::string, std::filesystem::path>> files;
  if (!spec.is_object()) return files;
  const SourceContext context{base_dir};
  for (const auto& [key, reader] : kSources)
    if (reader != read_builtin && spec.contains(key) && spec[key].is_string())
      files.emplace_back(key, context.resolve(spec[key].get<std::string>()));
  return files;
}

void make_dummy_paths_absolute(nlohmann::json& spec, const std::filesystem::path& base_dir) {
  for (const auto& [key, path] : dummy_file_paths(spec, base_dir))
    spec[key] = std::filesystem::absolute(path).string();
}

Dummy make_dummy(const nlohmann::json& spec, const std::string& file, const std::string& path,
                 const std::filesystem::path& base_dir) {
  DummySections sections = make_dummy_sections(spec, file, path, base_dir);
  try {
    return Dummy(std::move(sections));
  } catch (const std::invalid_argument& e) {
    // Sections the spec's checks passed but resampling made invalid (heights a rounding error
    // apart become equal): still the spec's fault.
    throw InputError(file, path, std::string(e.what()) + " (after resampling the dummy's sections)");
  }
}

DummySections cylinder_sections(double radius, double cx, double cz, double y_top,
                                double y_bottom, int sections, int points) {
  DummySections out;
  for (int k = 0; k < sections; ++k) {
    out.y.push_back(y_top - k * (y_top - y_bottom) / (sections - 1));
    out.cx.push_back(cx);
    out.cz.push_back(cz);
  }
  out.radius = Eigen::MatrixXd::Constant(sections, points, radius);
  return out;
}

DummySections sphere_sections(double radius, const Vec3& center, int sections, int points) {
  // Cell-centred polar angles: no section sits on a pole, where all `points` particles of a
  // section would coincide, and the sections are symmetric about the equator.
  DummySections out;
  out.radius.resize(sections, points);
  for (int k = 0; k < sections; ++k) {
    const double phi = kPi * (k + 0.5) / sections;
    out.y.push_back(center.y() + radius * std::cos(phi));
    out.cx.push_back(center.x());
    out.cz.push_back(center.z());
    out.radius.row(k).setConstant(radius * std::sin(phi));
  }
  return out;
}

DummySections read_sections_file(const std::string& file) {
  const nlohmann::json root_json = read_json_file(file);
  JsonReader root(root_json, file, "");
  const nlohmann::json& list = root.raw("sections");
  if (!list.is_array() || list.size() < 2)
    throw root.error("sections", "expected an array of at least 2 sections");
  root.finish();

  DummySections out;
  const int n = static_cast<int>(list.size());
  for (int k = 0; k < n; ++k) {
    JsonReader section(list[k], file, "sections[" + std::to_string(k) + "]");
    // The bounds of every dummy (docs/scene.md, Limits): beyond them the surface's spline and
    // the particles' grid are built over absurd extents (1e200 m took for ever).
    const double y = section.within("y", section.number("y"), limits::max_coordinate);
    if (k > 0 && !(y < out.y.back()))
      throw section.error("y", "must be below the previous section's (sections run top first)");
    const std::vector<double> center = section.has("center") ? section.numbers("center")
                                                             : std::vector<double>{0.0, 0.0};
    if (center.size() != 2) throw section.error("center", "expected 2 numbers [cx, cz]");
    for (const double c : center) section.within("center", c, limits::max_coordinate);
    const std::vector<double> radii = section.numbers("radii");
    if (k == 0) {
      if (radii.size() < 3) throw section.error("radii", "expected at least 3 radii");
      out.radius.resize(n, static_cast<Eigen::Index>(radii.size()));
    } else if (static_cast<Eigen::Index>(radii.size()) != out.radius.cols()) {
      throw section.error("radii", "expected " + std::to_string(out.radius.cols()) +
                                       " radii, like sections[0]");
    }
    for (size_t j = 0; j < radii.size(); ++j) {
      if (radii[j] < 0.0) throw section.error("radii", "must not be negative");
      out.radius(k, static_cast<Eigen::Index>(j)) =
          section.at_most("radii", radii[j], limits::max_length);
    }
    section.finish();
    out.y.push_back(y);
    out.cx.push_back(center[0]);
    out.cz.push_back(center[1]);
  }
  return out;
}

DummySections resample_sections(const DummySections& profile, int sections, int points) {
  const Dummy source(profile);
  const double y_top = profile.y.front();
  const double y_bottom = profile.y.back();
  DummySections out;
  out.radius.resize(sections, points);
  for (int k = 0; k < sections; ++k) {
    // The last height is set exactly: the formula may round past the profile's bottom.
    const double y =
        k + 1 == sections ? y_bottom : y_top - k * (y_top - y_bottom) / (sections - 1);
    const Eigen::Vector2d axis = source.axis_at(y);
    out.y.push_back(y);
    out.cx.push_back(axis.x());
    out.cz.push_back(axis.y());
    for (int j = 0; j < points; ++j)
      out.radius(k, j) = source.surface_radius(y, 2.0 * kPi * j / points);
  }
  return out;
}

void place_sections(DummySections& sections, double scale, const Vec3& offset) {
  for (int k = 0; k < sections.num_sections(); ++k) {
    sections.y[k] = scale * sections.y[k] + offset.y();
    sections.cx[k] = scale * sections.cx[k] + offset.x();
    sections.cz[k] = scale * sections.cz[k] + offset.z();
  }
  sections.radius *= scale;
}

}  // namespace drape
