#include "experiments/sweep/run_validation.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>

#include <fmt/format.h>

#include "core/io/input_error.hpp"
#include "core/scene/scene.hpp"
#include "experiments/run/run_limits.hpp"
#include "experiments/run/scene_simulation.hpp"
#include "experiments/sweep/ensemble_summary.hpp"
#include "integrators/registry/options_reader.hpp"

namespace drape {

namespace {

// The field of the experiment (or of its cases file) that gave `run` its override of `key`:
// an error in that value is the experiment's, not the scene's it was applied to.
std::pair<std::string, std::string> override_origin(const Experiment& e, const RunSpec& run,
                                                    const std::string& key) {
  const auto sets = [&](const std::vector<Override>& list) {
    return std::any_of(list.begin(), list.end(), [&](const Override& o) { return o.first == key; });
  };
  if (run.is_reference && sets(e.reference)) return {e.file, "reference." + key};
  for (const auto& swept : e.sweep)
    if (swept.first == key) return {e.file, "sweep." + key};
  if (key == repeat_parameter) return {e.file, "repeats"};
  if (key == "duration" && e.source.contains("duration")) return {e.file, "duration"};
  if (sets(e.set)) return {e.file, "set." + key};
  for (std::size_t c = 0; c < e.cases.size(); ++c)
    for (const auto& [case_key, value] : e.cases[c])
      if (case_key == key && std::find(run.parameters.begin(), run.parameters.end(),
                                       Override(key, value)) != run.parameters.end())
        return {e.cases_file.empty() ? e.file : e.cases_file, fmt::format("cases[{}].{}", c, key)};
  return {e.file, key};  // restart_error, which plan_run adds
}

// What a run builds from its scene that can fail on its input (scene_simulation.hpp), without
// the cloth and the integrator, which parse_scene and read_integrator_options have checked. The
// dummy and the recording are built once per distinct object: a sweep's runs mostly share them.
class RunInputCheck {
 public:
  void check(const Scene& scene) {
    const IntegratorOptions options = checked_integrator_options(scene);
    if (scene.restart_error.enabled())
      read_integrator_options(scene.restart_error.reference, scene.file, "restart_error.reference");
    if (!scene.dummy.is_null() && m_dummies.insert(key_of(scene.dummy, scene)).second)
      scene_dummy(scene);
    check_output_rows(scene, options, event_frames(scene));
  }

 private:
  // Relative paths inside the object resolve against the scene's folder, so it is part of the key.
  static std::string key_of(const nlohmann::json& object, const Scene& scene) {
    return scene.base_dir.string() + "\n" + object.dump();
  }

  // The recording is read once per distinct input; its bound on event frames is kept for the
  // output check of every run that plays it.
  double event_frames(const Scene& scene) {
    if (scene.input.is_null()) return 0.0;
    const std::string key = key_of(scene.input, scene);
    auto it = m_event_frames.find(key);
    if (it == m_event_frames.end())
      it = m_event_frames.emplace(key, event_frames_bound(scene_hand_input(scene)->track)).first;
    return it->second;
  }

  std::set<std::string> m_dummies;
  std::map<std::string, double> m_event_frames;
};

// Whether `run`'s scene with `assignments` (a subset of its own) passes the check.
bool passes_with(const RunSpec& run, const std::vector<std::string>& assignments) {
  try {
    RunInputCheck().check(load_scene(run.scene_path.string(), assignments));
    return true;
  } catch (const InputError&) {
    return false;
  }
}

}  // namespace

void validate_runs(const Experiment& experiment, const std::vector<RunSpec>& runs) {
  RunInputCheck inputs;
  for (const RunSpec& run : runs) {
    // A bisection's probes span [low, high]: both ends are checked, each naming its field, and
    // the first probe between them, sqrt(low high), which no integer key (cloth.rows) accepts.
    struct Variant {
      std::vector<std::string> assignments;
      const char* end;  ///< which probe, "" without a bisection
      double probe_at;  ///< the probe's value, with a bisection
    };
    std::vector<Variant> variants;
    if (run.bisect) {
      const double low = run.bisect->low, high = run.bisect->high, middle = std::sqrt(low * high);
      variants.push_back({run.assignments(low), "bisect.low", low});
      variants.push_back({run.assignments(high), "bisect.high", high});
      variants.push_back({run.assignments(middle), "the first probe between bisect.low and bisect.high", middle});
    } else {
      variants.push_back({run.assignments(), "", 0.0});
    }
    for (const auto& [assignments, end, probe_at] : variants) {
      try {
        inputs.check(load_scene(run.scene_path.string(), assignments));
      } catch (const InputError& e) {
        if (e.file() != run.scene_path.string()) throw;
        const std::optional<std::size_t> k = override_behind(assignments, e.field());
        // The bisection's probe is the last assignment. An error in another field (rows x cols
        // when cloth.rows is probed) is the probe's too when the run without it is good.
        const bool probe =
            run.bisect && (k ? *k >= run.overrides.size() : passes_with(run, run.assignments()));
        const std::string in_scene = " (in " + run.scene + ")";
        if (!k && !probe) {
          if (passes_with(run, {})) {
            // No one value is at fault (pins off a grid a sweep made smaller): the experiment's
            // values together are, and the message lists them.
            std::string values;
            for (const auto& [key, value] : run.overrides) values += " " + key + "=" + value.dump();
            throw InputError(experiment.file, "",
                             e.what() + std::string(", with the run's values:") + shorten(values));
          }
          throw;  // the scene's own error
        }
        if (probe) {
          throw InputError(experiment.file, "bisect",
                           fmt::format("{} = {} ({}): {}{}{}", run.bisect->parameter,
                                       probe_at, end, e.field() == run.bisect->parameter ? "" : e.field() + ": ",
                                       e.message(), in_scene));
        }
        const std::string key = run.overrides[*k].first;
        const auto [file, field] = override_origin(experiment, run, key);
        throw InputError(file, field + e.field().substr(std::min(key.size(), e.field().size())),
                         e.message() + in_scene);
      }
    }
  }
}

}  // namespace drape
