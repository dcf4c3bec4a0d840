#pragma once
// The dummy sources of docs/model.md section 3, chosen by a scene's `dummy` object: the built-in dress form
// (default), cylinder and sphere, a sections file and a sliced surface mesh. Every source yields
// DummySections at the requested resolution; `scale` (about the origin) and then `offset` place
// it in the scene.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "core/dummy/dummy.hpp"

namespace drape {

/// Default number of sections and of points per section (the paper's dummy: 80 x 32).
inline constexpr int kDefaultDummySections = 80;
inline constexpr int kDefaultDummyPoints = 32;

/// Builds the dummy that a scene's `dummy` object describes (`{}` gives the dress form).
/// `file` and `path` (the object's dotted path, normally "dummy") name it in errors; relative
/// file names inside it resolve against `base_dir`. Bad input throws InputError.
Dummy make_dummy(const nlohmann::json& spec, const std::string& file,
                 const std::string& path, const std::filesystem::path& base_dir);

/// The sections of that dummy, placed in the scene (what make_dummy builds its Dummy from).
DummySections make_dummy_sections(const nlohmann::json& spec, const std::string& file,
                                  const std::string& path, const std::filesystem::path& base_dir);

/// A vertical cylinder: section k at y_top - k (y_top - y_bottom) / (sections - 1), radius R.
DummySections cylinder_sections(double radius, double cx, double cz, double y_top,
                                double y_bottom, int sections, int points);

/// A sphere sliced at polar angles phi_k = pi (k + 1/2) / sections, which avoids the poles.
DummySections sphere_sections(double radius, const Vec3& center, int sections, int points);

/// Reads a sections file (format in docs/dress_form.md) at its own resolution, in metres.
DummySections read_sections_file(const std::string& file);

/// Resamples a stack to `sections` evenly spaced heights from its top to its bottom and
/// `points` angles, linearly in height and angle (Dummy::surface_radius and Dummy::axis_at).
DummySections resample_sections(const DummySections& profile, int sections, int points);

/// Scales heights, centres and radii about the origin, then translates by offset.
void place_sections(DummySections& sections, double scale, const Vec3& offset);

/// The files a dummy spec names (`file`, `mesh`), by key, relative names resolved against
/// `base_dir` (the scene's folder); none for a builtin, null or malformed spec.
std::vector<std::pair<std::string, std::filesystem::path>> dummy_file_paths(
    const nlohmann::json& spec, const std::filesystem::path& base_dir);

/// Rewrites the file names of a dummy spec (`file`, `mesh`) that are relative to `base_dir` as
/// absolute paths, for a copy of the scene written elsewhere (a live run's replay scene).
void make_dummy_paths_absolute(nlohmann::json& spec, const std::filesystem::path& base_dir);

}  // namespace drape
