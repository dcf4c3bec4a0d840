#pragma once
// An experiment file: scenes, the parameter values to sweep, explicit cases, and the plan of
// independent runs they expand to (docs/experiments.md).
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace drape {

/// One `--set` override of a run: a dotted scene path and its JSON value.
using Override = std::pair<std::string, nlohmann::json>;

/// A bisection on one scene value: the largest value for which the run stays stable.
struct BisectSpec {
  std::string parameter = "integrator.dt";  ///< the scene value searched
  double low = 0.0;                         ///< expected stable (checked first)
  double high = 0.0;                        ///< expected unstable (checked second)
  int steps = 8;                            ///< probes per search
  std::optional<double> max_drift;          ///< a probe with larger energy drift counts as unstable
  /// A probe whose energy rose above its start by more than this (relative) counts as unstable.
  std::optional<double> max_rise;
};

/// An experiment as read from its file, paths resolved against the file's folder.
struct Experiment {
  std::string file;  ///< the experiment file (for messages)
  std::string name;
  std::string question;
  std::vector<std::string> scenes;               ///< as written in the file
  std::vector<std::filesystem::path> scene_paths;  ///< resolved against the file's folder
  std::vector<Override> set;                     ///< overrides applied to every run
  std::vector<std::pair<std::string, std::vector<nlohmann::json>>> sweep;  ///< cartesian product
  std::vector<std::vector<Override>> cases;      ///< explicit combinations, times the sweep
  std::string cases_file;  ///< the shared file the cases were read from, "" when inline
  std::vector<Override> reference;               ///< overrides that make a run's reference run
  /// With a reference: every other run measures its restart error (docs/analysis.md, "Restart
  /// error") over these horizons [s]; empty: none.
  std::vector<double> restart_horizons;
  std::optional<BisectSpec> bisect;
  int repeats = 0;  ///< 0: no ensemble; N: every run N times with perturbation.seed = 1..N
  std::vector<std::string> metrics;              ///< what the report computes and plots
  nlohmann::json source;                         ///< the file as read
};

/// One run of the plan: a scene and the overrides applied to it.
struct RunSpec {
  int index = 0;                    ///< position in the whole plan (shards use it)
  std::string id;                   ///< stable folder name: slug of the overrides and a hash
  std::string scene;                ///< as written in the experiment file
  std::filesystem::path scene_path;
  /// FNV-1a of the scene file's bytes (hex): a run of an edited scene is another run, so that
  /// resume and merge never take its old results (run.json and the id hold it).
  std::string scene_digest;
  /// The files the scene names with the run's overrides (`dummy.file`, `dummy.mesh`,
  /// `input.recording`), field -> FNV-1a of the file's bytes: a run of an edited recording or
  /// mesh is another run too. Empty (and absent from run.json, so the ids of runs naming no
  /// file stay as they were) when the scene names none.
  nlohmann::json file_digests = nlohmann::json::object();
  std::vector<Override> parameters;  ///< the swept and case values, in plan order
  std::vector<Override> overrides;   ///< everything applied: set, duration, parameters
  std::string reference;            ///< id of this run's reference run, "" for none
  bool is_reference = false;
  std::optional<BisectSpec> bisect;

  /// The overrides as `key=value` strings for load_scene.
  std::vector<std::string> assignments() const;
  /// The same with the bisection's parameter set to `probe` last (a bisecting run only).
  std::vector<std::string> assignments(double probe) const;
  /// What run.json holds: enough to tell whether a finished folder is this run.
  nlohmann::json to_json() const;
};

/// A slice of the plan: runs whose index % count == index_1based - 1.
struct Shard {
  int index = 1;  ///< 1-based, as in Slurm's and GNU parallel's numbering
  int count = 1;

  bool contains(int run_index) const { return run_index % count == index - 1; }
  /// "3-of-8": the file name of this shard's results.
  std::string tag() const;
};

/// Whether two dotted scene paths are equal or one holds the other (integrator and
/// integrator.dt).
bool paths_overlap(const std::string& a, const std::string& b);

/// The known metric names of an experiment's `metrics` list (computed by analysis/).
const std::vector<std::string>& known_metrics();

/// Parses and validates an experiment; throws InputError naming `file` and the field.
Experiment parse_experiment(const nlohmann::json& source, const std::string& file,
                            const std::filesystem::path& base_dir);
/// Reads and parses an experiment file.
Experiment load_experiment(const std::string& file);
/// Expands scenes x cases x sweep (plus the reference runs they need) into the plan.
std::vector<RunSpec> expand_runs(const Experiment& experiment);
/// Parses `K/N` (1 <= K <= N); throws InputError naming `--shard`.
Shard parse_shard(const std::string& text);
/// The stable id of a run: readable slug of scene and values, then an 8-hex-digit hash of
/// everything that defines the run (not of its place in the plan).
std::string run_id(const RunSpec& run);

}  // namespace drape
