#pragma once
// A scene file (docs/model.md section 9): the problem data of one run. Solver options (`integrator`) and the hand
// input (`input`) are kept as validated JSON here and read by their own layers, so that core
// knows nothing of integrators.
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/cloth/cloth.hpp"
#include "core/io/input_error.hpp"
#include "core/model/cloth_system.hpp"
#include "core/manipulations/manipulation_params.hpp"

namespace drape {

/// What a run writes besides summary.json and state.csv.
struct OutputOptions {
  double energy_interval = 0.01;  ///< time between energy.csv rows [s]; 0 = every step
  double trace_interval = 0.0;    ///< time between trace.csv frames [s]; 0 = no trace.csv
  double vtk_interval = 0.0;      ///< time between VTK frames [s]; 0 = no frames
  /// Time between event_trace/ frames [s] in the window after each event; 0 = no event_trace/.
  double event_trace_interval = 0.0;
  double event_trace_window = 0.5;  ///< length of that window [s]
};

/// A seeded perturbation of the initial state, for ensembles and hard starts (docs/scene.md; off
/// by default).
struct Perturbation {
  double position = 0.0;   ///< amplitude as a fraction of cloth.spacing; 0: none
  std::uint64_t seed = 0;  ///< the same seed gives the same perturbation
  bool gaussian = false;   ///< false: uniform in [-a, a] per coordinate; true: normal, std a
  /// Every particle's position scaled about the pins' centroid by 1 + stretch, the pins moving
  /// with the cloth: every spring starts this fraction longer (negative: shorter); 0: none.
  double stretch = 0.0;
  /// Amplitude of the seeded initial velocity of the free particles [m/s], drawn as the
  /// positions are; 0: at rest.
  double velocity = 0.0;
  /// Also perturb right after each map, which lays every particle out anew and so erases the
  /// initial perturbation (the k-th map draws from stream k of the seed).
  bool after_map = false;
};

/// The restart error of the integrator against a reference (docs/analysis.md, "Restart
/// error"): the reference integrator runs the scene, and the scene's own integrator restarts from
/// the reference's state at its start and after each of its events for each horizon. Off while
/// `reference` is null.
struct RestartErrorOptions {
  nlohmann::json reference;      ///< the reference's `integrator` object (read by integrators/)
  std::vector<double> horizons;  ///< ascending horizons [s]
  bool enabled() const { return !reference.is_null(); }
};

/// One scene: cloth, pins, forces, object, duration, manipulation, input and output.
struct Scene {
  std::string file;                ///< the scene file (for messages)
  std::string description;         ///< what the scene shows (free text)
  std::filesystem::path base_dir;  ///< relative paths in the scene resolve against this
  ClothParams cloth;
  std::vector<GridPoint> pins;
  ForceParams forces;
  nlohmann::json dummy;       ///< the `dummy` object, null for no object
  nlohmann::json integrator;  ///< the `integrator` object
  nlohmann::json input;       ///< the `input` object, null when absent
  double duration = 0.0;
  /// The free fall the runaway bound allows for [s], at least `duration` (docs/outputs.md).
  double runaway_horizon = 0.0;
  ManipulationParams manipulation;
  OutputOptions output;
  Perturbation perturbation;
  RestartErrorOptions restart_error;
  nlohmann::json source;  ///< the whole scene as read, overrides applied
};

/// Applies one `--set key.path=value` override (value parsed as JSON, else a string).
void apply_override(nlohmann::json& scene, const std::string& assignment);
/// The index of the last of `overrides` (key.path=value) whose path holds `field`: the path
/// itself, or a key or an index inside its value. An error in that field is in the value the
/// override gave (the last override of a path wins), so it names the override, not the scene.
std::optional<std::size_t> override_holding(const std::vector<std::string>& overrides,
                                            const std::string& field);
/// override_holding, or else the last of `overrides` that made the object at `field`: an
/// override nosuch.key=1 makes a `nosuch` that the scene then calls an unknown key.
std::optional<std::size_t> override_behind(const std::vector<std::string>& overrides,
                                           const std::string& field);
/// Parses and validates a scene; throws InputError naming `file` and the field.
Scene parse_scene(const nlohmann::json& source, const std::string& file,
                  const std::filesystem::path& base_dir);
/// Reads a scene file, applies the overrides in order, and parses it.
Scene load_scene(const std::string& file, const std::vector<std::string>& overrides = {});

/// Throws InputError naming the second of two --set arguments with the same key path: one of
/// them would be dropped without a word (they apply in order, the last winning).
void check_distinct_overrides(const std::vector<std::string>& overrides);
/// Calls use(load_scene(file, overrides)) for a command line's --set arguments (each key path
/// once): an InputError
/// in a value a --set gave (while loading, or while `use` builds from the scene) names that
/// argument, not the scene file it was applied to.
template <class Use>
auto with_command_line_overrides(const std::string& file,
                                 const std::vector<std::string>& overrides, Use use) {
  check_distinct_overrides(overrides);
  try {
    return use(load_scene(file, overrides));
  } catch (const InputError& e) {
    const auto k = e.file() == file ? override_behind(overrides, e.field()) : std::nullopt;
    if (!k) throw;
    throw InputError("--set " + shorten(overrides[*k]), e.field(), e.message());
  }
}

}  // namespace drape
