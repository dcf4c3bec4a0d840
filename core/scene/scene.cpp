#include "core/scene/scene.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/fabrics/fabric.hpp"
#include "core/io/input_error.hpp"
#include "core/io/json_reader.hpp"
#include "core/io/json_text.hpp"
#include "core/io/scene_limits.hpp"

namespace drape {

namespace {

constexpr double direction_tolerance = 1e-6;

Vec3 unit_direction(JsonReader& in, const std::string& key, const Vec3& fallback) {
  const Vec3 dir = in.vec3(key, fallback);
  if (std::abs(dir.norm() - 1.0) > direction_tolerance)
    throw in.error(key, "must be a unit vector, has length " + std::to_string(dir.norm()));
  return dir;
}

const Fabric& read_fabric(JsonReader& in) {
  const std::string name = in.string("fabric");
  const Fabric* fabric = find_fabric(name);
  if (!fabric)
    throw in.error("fabric", "unknown fabric '" + name + "' (known: " + fabric_names() + ")");
  return *fabric;
}

// The scene as run: a preset's derived values written into summary.json's scene.
void fill_fabric_values(nlohmann::json& cloth, const ClothParams& c) {
  cloth["particle_mass"] = c.particle_mass;
  cloth["k_structural"] = c.k_structural;
  cloth["k_shear"] = c.k_shear;
  cloth["k_bending"] = c.k_bending;
}

// Stiffness and damping: >= 0 (or > 0) and below the bound whose products stay finite.
double stiffness(JsonReader& in, const std::string& key, double value, bool positive) {
  if (positive) in.positive(key, value);
  return in.at_most(key, in.non_negative(key, value), limits::max_stiffness);
}

ClothParams read_cloth(JsonReader in) {
  ClothParams c;
  c.rows = static_cast<int>(in.integer_in("rows", 1, limits::max_cloth_particles));
  c.cols = static_cast<int>(in.integer_in("cols", 1, limits::max_cloth_particles));
  const std::int64_t particles = std::int64_t{c.rows} * c.cols;
  if (particles < 2) throw in.error("cols", "a cloth needs at least 2 particles");
  if (particles > limits::max_cloth_particles)
    throw in.error("cols", "rows x cols = " + std::to_string(particles) +
                               " particles, more than the limit " +
                               std::to_string(limits::max_cloth_particles));
  c.spacing = in.at_least(
      "spacing", in.at_most("spacing", in.number("spacing"), limits::max_length),
      limits::min_spacing);
  c.origin = in.within("origin", in.vec3("origin"), limits::max_coordinate);
  const double resolved = limits::min_spacing_of_origin * c.origin.cwiseAbs().maxCoeff();
  if (!(c.spacing >= resolved))
    throw in.error("spacing", fmt::format("must be at least 2^-30 of cloth.origin's largest "
                                          "coordinate ({:g} m) there, got {:g}",
                                          resolved, c.spacing));
  c.col_dir = unit_direction(in, "col_dir", c.col_dir);
  c.row_dir = unit_direction(in, "row_dir", c.row_dir);
  if (std::abs(c.col_dir.dot(c.row_dir)) > direction_tolerance)
    throw in.error("row_dir", "must be orthogonal to cloth.col_dir");
  // A fabric preset supplies the mass and stiffness defaults; explicit keys still win.
  const bool preset = in.has("fabric");
  const FabricSprings d = preset ? fabric_springs(read_fabric(in), c.spacing) : FabricSprings{};
  // A value the preset derives from the spacing (not given in the scene) that is out of range is
  // the spacing's doing, and the error names it.
  const auto derived = [&](const char* key, const auto& read) {
    if (!preset || in.has(key)) return read();
    try {
      return read();
    } catch (const InputError& e) {
      throw in.error("spacing", std::string("gives the fabric's ") + key + ", which " + e.message());
    }
  };
  c.particle_mass = derived("particle_mass", [&] {
    return in.at_least("particle_mass",
                       in.at_most("particle_mass",
                                  preset ? in.number("particle_mass", d.particle_mass)
                                         : in.number("particle_mass"),
                                  limits::max_mass),
                       limits::min_mass);
  });
  c.k_structural = derived("k_structural", [&] {
    return stiffness(in, "k_structural",
                     preset ? in.number("k_structural", d.k_structural) : in.number("k_structural"),
                     true);
  });
  c.k_shear = derived("k_shear", [&] {
    return stiffness(in, "k_shear", in.number("k_shear", preset ? d.k_shear : c.k_structural), false);
  });
  c.k_bending = derived("k_bending", [&] {
    return stiffness(in, "k_bending", in.number("k_bending", d.k_bending), false);
  });
  c.damping_spring = stiffness(in, "damping_spring", in.number("damping_spring", 0.0), false);
  c.damping_air = stiffness(in, "damping_air", in.number("damping_air", 0.0), false);
  in.finish();
  return c;
}

GridPoint read_grid_point(const nlohmann::json& value, const ClothParams& cloth,
                          const std::string& file, const std::string& field) {
  const auto bad = [&] {
    return InputError(file, field, "expected [row, col] integers, got " + quote_json(value));
  };
  if (!value.is_array() || value.size() != 2 || !value[0].is_number_integer() ||
      !value[1].is_number_integer())
    throw bad();
  const std::int64_t row = exact_integer(value[0]).value_or(-1);
  const std::int64_t col = exact_integer(value[1]).value_or(-1);
  if (!exact_integer(value[0]) || !exact_integer(value[1])) throw bad();
  // Compared in 64 bits: a row of 4294967296 must not wrap to 0 on the way to an int.
  if (row < 0 || row >= cloth.rows || col < 0 || col >= cloth.cols)
    throw InputError(file, field,
                     "[" + std::to_string(row) + ", " + std::to_string(col) +
                         "] is off the " + std::to_string(cloth.rows) + " x " +
                         std::to_string(cloth.cols) + " grid");
  return GridPoint{static_cast<int>(row), static_cast<int>(col)};
}

std::vector<GridPoint> read_pins(JsonReader& in, const ClothParams& cloth) {
  std::vector<GridPoint> pins;
  if (!in.has("pins")) return pins;
  const auto& list = in.raw("pins");
  if (!list.is_array()) throw in.error("pins", "expected a list of [row, col]");
  for (std::size_t k = 0; k < list.size(); ++k) {
    const std::string field = in.field("pins") + "[" + std::to_string(k) + "]";
    pins.push_back(read_grid_point(list[k], cloth, in.file(), field));
    // A pin given twice is one pin: the list would say more than the scene does.
    for (std::size_t j = 0; j < k; ++j)
      if (pins[j].row == pins[k].row && pins[j].col == pins[k].col)
        throw InputError(in.file(), field, "repeats pins[" + std::to_string(j) + "]");
  }
  return pins;
}

CollisionParams read_collision(JsonReader in) {
  CollisionParams c;
  c.threshold = in.positive("threshold", in.number("threshold", c.threshold));
  in.at_most("threshold", c.threshold, limits::max_length);
  c.stiffness = stiffness(in, "stiffness", in.number("stiffness", c.stiffness), false);
  const std::string model = in.string("model", "particle");
  if (model == "surface")
    c.model = CollisionModel::surface;
  else if (model == "smooth")
    c.model = CollisionModel::smooth;
  else if (model != "particle")
    throw in.error("model",
                   "unknown collision model '" + model + "' (known: particle, surface, smooth)");
  c.friction = in.non_negative("friction", in.number("friction", c.friction));
  in.at_most("friction", c.friction, limits::max_friction);
  c.friction_epsilon = in.positive("friction_epsilon",
                                   in.number("friction_epsilon", c.friction_epsilon));
  in.at_least("friction_epsilon", c.friction_epsilon, limits::min_friction_epsilon);
  in.at_most("friction_epsilon", c.friction_epsilon, limits::max_friction_epsilon);
  in.finish();
  return c;
}

ManipulationParams read_manipulation(JsonReader in, const ClothParams& cloth) {
  ManipulationParams m;
  m.hold_threshold =
      in.positive("hold_threshold", in.number("hold_threshold", m.hold_threshold));
  in.at_most("hold_threshold", m.hold_threshold, limits::max_length);
  if (in.has("release")) {
    const auto& release = in.raw("release");
    if (release.is_string()) {
      if (release.get<std::string>() != "held")
        throw in.error("release", "expected \"held\" or a pin [row, col]");
    } else {
      m.release_held = false;
      m.release_pin = read_grid_point(release, cloth, in.file(), in.field("release"));
    }
  }
  m.attach_iterations = in.integer("attach_iterations", m.attach_iterations);
  if (m.attach_iterations < 0) throw in.error("attach_iterations", "must not be negative");
  m.attach_time = in.non_negative("attach_time", in.number("attach_time", m.attach_time));
  in.at_most("attach_time", m.attach_time, limits::max_duration);
  m.hold_ramp = in.non_negative("hold_ramp", in.number("hold_ramp", m.hold_ramp));
  in.at_most("hold_ramp", m.hold_ramp, limits::max_duration);
  m.attach_at_contact_distance =
      in.boolean("attach_at_contact_distance", m.attach_at_contact_distance);
  m.map_top = in.number("map_top", m.map_top);
  in.within("map_top", m.map_top, limits::max_coordinate);
  m.map_direction = in.integer("map_direction", m.map_direction);
  if (m.map_direction != 1 && m.map_direction != -1)
    throw in.error("map_direction", "must be +1 or -1");
  in.finish();
  return m;
}

Perturbation read_perturbation(JsonReader in) {
  Perturbation p;
  p.position = in.at_most("position", in.non_negative("position", in.number("position", 0.0)),
                          limits::max_perturbation);
  const int seed = in.integer("seed", 0);
  if (seed < 0) throw in.error("seed", "must not be negative");
  p.seed = static_cast<std::uint64_t>(seed);
  const std::string distribution = in.string("distribution", "uniform");
  if (distribution != "uniform" && distribution != "gaussian")
    throw in.error("distribution", "expected \"uniform\" or \"gaussian\"");
  p.gaussian = distribution == "gaussian";
  p.after_map = in.boolean("after_map", false);
  p.stretch = in.within("stretch", in.number("stretch", 0.0), limits::max_stretch);
  p.velocity = in.at_most("velocity", in.non_negative("velocity", in.number("velocity", 0.0)),
                          limits::max_velocity_perturbation);
  in.finish();
  return p;
}

RestartErrorOptions read_restart_error(JsonReader in, double duration) {
  RestartErrorOptions r;
  r.reference = in.raw("reference");
  if (!r.reference.is_object()) throw in.error("reference", "expected an integrator object");
  r.horizons = in.numbers("horizons");
  if (r.horizons.empty() || r.horizons.size() > limits::max_restart_horizons)
    throw in.error("horizons", "expected 1 to " + std::to_string(limits::max_restart_horizons) +
                                   " horizons");
  for (std::size_t k = 0; k < r.horizons.size(); ++k) {
    const std::string key = "horizons[" + std::to_string(k) + "]";
    // A horizon below the shortest step the run may take (Limits) measures no motion.
    if (!(r.horizons[k] >= duration * limits::min_relative_step) || r.horizons[k] > duration)
      throw in.error(key, "must be in [duration x 2^-50, duration = " +
                              nlohmann::json(duration).dump() + " s]");
    if (k > 0 && !(r.horizons[k] > r.horizons[k - 1]))
      throw in.error(key, "horizons must ascend");
  }
  in.finish();
  return r;
}

// An output interval: 0 (every step, or none) or long enough to advance time and to keep the
// file within limits::max_output_rows.
double output_interval(JsonReader& in, const std::string& key, double fallback, double duration,
                       double rows_per_frame) {
  const double interval = in.non_negative(key, in.number(key, fallback));
  if (interval == 0.0) return interval;
  if (interval < duration * limits::min_relative_step)
    throw in.error(key, "too small to advance time over duration " +
                            nlohmann::json(duration).dump() + " s (at least duration x 2^-50)");
  const double rows = (duration / interval + 1.0) * rows_per_frame;
  if (rows > limits::max_output_rows)
    throw in.error(key, "would write " + nlohmann::json(rows).dump() +
                            " rows (particles x frames), more than " +
                            nlohmann::json(limits::max_output_rows).dump());
  return interval;
}

OutputOptions read_output(JsonReader in, double duration, const ClothParams& cloth) {
  OutputOptions o;
  const double particles = static_cast<double>(cloth.rows) * cloth.cols;
  o.energy_interval = output_interval(in, "energy_interval", o.energy_interval, duration, 1.0);
  o.trace_interval = output_interval(in, "trace_interval", 0.0, duration, particles);
  o.vtk_interval = output_interval(in, "vtk_interval", 0.0, duration, particles);
  // Windows restart at each event, so the event trace never has more frames than a trace at its
  // interval over the whole run (plus one a event).
  o.event_trace_interval = output_interval(in, "event_trace_interval", 0.0, duration, particles);
  o.event_trace_window = in.at_most(
      "event_trace_window", in.positive("event_trace_window", in.number("event_trace_window", 0.5)),
      limits::max_duration);
  in.finish();
  return o;
}

}  // namespace

void apply_override(nlohmann::json& scene, const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InputError("--set", assignment, "expected key.path=value");
  const std::string path = assignment.substr(0, eq);
  const std::string text = assignment.substr(eq + 1);
  // Each key opens an object: the nesting limit of every JSON input holds for the path too
  // (50000 levels overflowed the stack where the scene is copied and destroyed).
  if (std::count(path.begin(), path.end(), '.') >= max_json_depth)
    throw InputError("--set", path, fmt::format("a key path deeper than {} levels", max_json_depth));
  // A --set string is the shell's bytes, which the run would fail to write into summary.json.
  if (!is_utf8(assignment)) throw InputError("--set", path, "not valid UTF-8 text");
  nlohmann::json value = try_parse_json_text(text, "--set", path).value_or(nlohmann::json(text));

  nlohmann::json* node = &scene;
  std::size_t start = 0;
  while (true) {
    const auto dot = path.find('.', start);
    const std::string key = path.substr(start, dot == std::string::npos ? dot : dot - start);
    if (key.empty()) throw InputError("--set", path, "empty key in the path");
    if (node->is_null()) *node = nlohmann::json::object();
    if (!node->is_object())
      throw InputError("--set", path, "'" + key + "' is inside a value that is not an object");
    node = &(*node)[key];
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  *node = std::move(value);
}

std::optional<std::size_t> override_holding(const std::vector<std::string>& overrides,
                                            const std::string& field) {
  for (std::size_t k = overrides.size(); k-- > 0;) {
    const std::string path = overrides[k].substr(0, overrides[k].find('='));
    if (field.rfind(path, 0) != 0) continue;
    if (field.size() == path.size() || field[path.size()] == '.' || field[path.size()] == '[')
      return k;
  }
  return std::nullopt;
}

std::optional<std::size_t> override_behind(const std::vector<std::string>& overrides,
                                           const std::string& field) {
  if (const auto k = override_holding(overrides, field)) return k;
  for (std::size_t k = overrides.size(); k-- > 0;)
    if (overrides[k].rfind(field + ".", 0) == 0) return k;
  return std::nullopt;
}

Scene parse_scene(const nlohmann::json& source, const std::string& file,
                  const std::filesystem::path& base_dir) {
  JsonReader in(source, file, "");
  Scene s;
  s.file = file;
  s.base_dir = base_dir;
  s.source = source;
  s.description = in.string("description", "");
  s.cloth = read_cloth(in.object("cloth"));
  if (s.source["cloth"].contains("fabric")) fill_fabric_values(s.source["cloth"], s.cloth);
  s.pins = read_pins(in, s.cloth);
  s.forces.gravity = in.vec3("gravity", s.forces.gravity);
  in.within("gravity", s.forces.gravity, limits::max_gravity);
  s.dummy = in.has("dummy") ? in.raw("dummy") : nlohmann::json{{"builtin", "dress-form"}};
  if (!s.dummy.is_null() && !s.dummy.is_object())
    throw in.error("dummy", "expected an object or null");
  if (in.has("collision")) s.forces.collision = read_collision(in.object("collision"));
  s.integrator = in.raw("integrator");
  if (!s.integrator.is_object()) throw in.error("integrator", "expected an object");
  s.duration = in.non_negative("duration", in.number("duration"));
  in.at_most("duration", s.duration, limits::max_duration);
  // A live run's replay stops where the live run did but keeps the live run's bound (docs/live.md).
  s.runaway_horizon = in.at_most("runaway_horizon", in.number("runaway_horizon", s.duration),
                                 limits::max_duration);
  if (!(s.runaway_horizon >= s.duration))
    throw in.error("runaway_horizon", "must be at least duration (" +
                                          nlohmann::json(s.duration).dump() + " s)");
  if (in.has("input")) {
    s.input = in.raw("input");
    if (!s.input.is_object()) throw in.error("input", "expected an object");
  }
  if (in.has("manipulation"))
    s.manipulation = read_manipulation(in.object("manipulation"), s.cloth);
  s.output = read_output(in.has("output") ? in.object("output")
                                          : JsonReader(nlohmann::json::object(), file, "output"),
                         s.duration, s.cloth);
  if (in.has("perturbation")) s.perturbation = read_perturbation(in.object("perturbation"));
  if (in.has("restart_error"))
    s.restart_error = read_restart_error(in.object("restart_error"), s.duration);
  in.finish();
  return s;
}

void check_distinct_overrides(const std::vector<std::string>& overrides) {
  const auto path_of = [](const std::string& assignment) {
    return assignment.substr(0, assignment.find('='));
  };
  for (std::size_t k = 0; k < overrides.size(); ++k)
    for (std::size_t j = 0; j < k; ++j)
      if (path_of(overrides[j]) == path_of(overrides[k]))
        throw InputError("--set " + shorten(overrides[k]), path_of(overrides[k]),
                         "given twice (also --set " + shorten(overrides[j]) + ")");
}

Scene load_scene(const std::string& file, const std::vector<std::string>& overrides) {
  nlohmann::json source = read_json_file(file);
  // A file that is no object is the file's fault, before any --set finds it not an object.
  JsonReader{source, file, ""};
  for (const auto& assignment : overrides) apply_override(source, assignment);
  return parse_scene(source, file, std::filesystem::path(file).parent_path());
}

}  // namespace drape
