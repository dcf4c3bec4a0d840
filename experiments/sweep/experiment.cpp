#include "experiments/sweep/experiment.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <optional>
#include <set>
#include <tuple>
#include <utility>

#include "core/io/input_error.hpp"
#include "core/io/json_reader.hpp"
#include "core/scene/scene.hpp"
#include "core/io/scene_limits.hpp"
#include "experiments/sweep/ensemble_summary.hpp"
#include "experiments/sweep/plan_size.hpp"
#include "core/io/json_text.hpp"

namespace drape {

namespace {

// A scene path must be something load_scene's apply_override accepts: dotted, no empty part.
void check_key(const JsonReader& in, const std::string& field, const std::string& key) {
  if (key.empty() || key.front() == '.' || key.back() == '.' || key.find("..") != std::string::npos ||
      key.find('=') != std::string::npos)
    throw in.error(field, "'" + key + "' is not a scene path like integrator.dt");
  if (std::count(key.begin(), key.end(), '.') >= max_json_depth)  // as apply_override
    throw in.error(field, fmt::format("a key path deeper than {} levels", max_json_depth));
}

std::vector<Override> read_overrides(JsonReader& in, const std::string& key) {
  const nlohmann::json& object = in.raw(key);
  if (!object.is_object())
    throw in.error(key, "expected an object of scene paths and values, e.g. {\"integrator.dt\": 0.001}");
  std::vector<Override> out;
  for (const auto& item : object.items()) {
    check_key(in, key + "." + item.key(), item.key());
    out.emplace_back(item.key(), item.value());
  }
  return out;
}

// The case objects of `in`'s "cases" list; `expected` says what else the field may hold.
std::vector<std::vector<Override>> read_case_list(JsonReader& in, const std::string& expected) {
  const nlohmann::json& cases = in.raw("cases");
  if (!cases.is_array() || cases.empty()) throw in.error("cases", expected);
  std::vector<std::vector<Override>> out;
  for (std::size_t c = 0; c < cases.size(); ++c) {
    const std::string field = fmt::format("cases[{}]", c);
    if (!cases[c].is_object())
      throw in.error(field, "expected an object of scene paths and values");
    std::vector<Override> one;
    for (const auto& item : cases[c].items()) {
      check_key(in, field + "." + item.key(), item.key());
      one.emplace_back(item.key(), item.value());
    }
    out.push_back(std::move(one));
  }
  return out;
}

// `cases` inline, or the name of a file beside the definition whose object holds them under
// "cases" (docs/experiments.md): several definitions then share one list, e.g. every implicit
// table, instead of each repeating it.
// Returns the cases and, when they come from a file, its path.
std::pair<std::vector<std::vector<Override>>, std::string> read_cases(
    JsonReader& in, const std::filesystem::path& base_dir) {
  const nlohmann::json& value = in.raw("cases");
  if (!value.is_string())
    return {read_case_list(in, "expected a non-empty list of objects or a cases file name"), ""};
  const std::string name = value.get<std::string>();
  if (name.empty() || std::filesystem::path(name).is_absolute())
    throw in.error("cases",
                   "expected a cases file name relative to this file, got \"" + name + "\"");
  const std::filesystem::path path = base_dir / name;
  if (const auto reason = unreadable_file_reason(path.string()))
    throw in.error("cases", *reason + ": " + path.string());
  const nlohmann::json source = read_json_file(path.string());
  JsonReader shared(source, path.string(), "");
  auto cases = read_case_list(
      shared, "expected a non-empty list of case objects (a cases file cannot name another file)");
  shared.finish();
  return {std::move(cases), path.string()};
}

BisectSpec read_bisect(JsonReader in) {
  BisectSpec b;
  b.parameter = in.string("parameter", b.parameter);
  check_key(in, "parameter", b.parameter);  // here, not as a --set the user never gave
  b.low = in.positive("low", in.number("low"));
  b.high = in.positive("high", in.number("high"));
  if (b.high <= b.low) throw in.error("high", "must be above bisect.low");
  b.steps = in.integer("steps", b.steps);
  if (b.steps < 1 || b.steps > 60) throw in.error("steps", "must be in 1..60");
  if (in.has("max_drift")) b.max_drift = in.positive("max_drift", in.number("max_drift"));
  if (in.has("max_rise")) b.max_rise = in.positive("max_rise", in.number("max_rise"));
  in.finish();
  return b;
}

// Whether `inner` is a path inside `outer` (integrator.dt inside integrator).
bool holds(const std::string& outer, const std::string& inner) {
  return inner.size() > outer.size() && inner.compare(0, outer.size(), outer) == 0 &&
         inner[outer.size()] == '.';
}

// Why `key` may not be given with `other` (given in `where`), or "" when it may.
std::string clash_of(const std::string& key, const std::string& other, const std::string& where) {
  if (!paths_overlap(key, other)) return "";
  if (key == other) return where == "sweep" ? "is also swept" : "is also in " + where;
  return "overlaps " + where + "." + other + " (one holds the other)";
}

// Every scene path of a run comes from one place: `set`, the sweep or its case.
void check_disjoint(const JsonReader& in, const Experiment& e) {
  // Each key of `mine` against each of `others` (given in `where`), and a list against itself.
  const auto check = [](const std::vector<Override>& mine, const std::vector<Override>& others,
                        const std::string& where, const auto& error) {
    for (const auto& [key, value] : mine)
      for (const auto& [other, other_value] : others) {
        const std::string why = clash_of(key, other, where);
        if (!why.empty()) throw error(key, why);
      }
  };
  const auto check_within = [](const std::vector<Override>& list, const std::string& where,
                               const auto& error) {
    for (std::size_t i = 0; i < list.size(); ++i)
      for (std::size_t j = i + 1; j < list.size(); ++j) {
        const std::string why = clash_of(list[i].first, list[j].first, where);
        if (!why.empty()) throw error(list[i].first, why);
      }
  };
  std::vector<Override> swept;
  for (const auto& [key, values] : e.sweep) swept.emplace_back(key, values.front());
  const auto in_set = [&](const std::string& key, const std::string& why) {
    return in.error("set." + key, why);
  };
  const auto in_sweep = [&](const std::string& key, const std::string& why) {
    return in.error("sweep." + key, why);
  };
  check(e.set, swept, "sweep", in_set);
  check_within(e.set, "set", in_set);
  check_within(swept, "sweep", in_sweep);
  // A clash in a shared cases file names that file's field and the definition.
  for (std::size_t c = 0; c < e.cases.size(); ++c) {
    const auto in_case = [&](const std::string& key, const std::string& why) {
      const std::string field = fmt::format("cases[{}].{}", c, key);
      if (e.cases_file.empty()) return in.error(field, why);
      return InputError(e.cases_file, field, why + " in " + in.file());
    };
    const std::vector<Override>& one = e.cases[c];
    check(one, swept, "sweep", in_case);
    check(one, e.set, "set", in_case);
    check_within(one, fmt::format("cases[{}]", c), in_case);
  }
  if (e.bisect) {
    // The probe is applied last: a value it replaces (the parameter itself, or a key inside it)
    // would be ignored by every probe. An object that holds the parameter is merged into.
    const std::string& p = e.bisect->parameter;
    const auto check_probe = [&](const std::vector<Override>& others, const std::string& where) {
      for (const auto& [other, value] : others)
        if (other == p || holds(p, other))
          throw in.error("bisect.parameter",
                         "'" + p + "' would replace " + where + "." + other + " in every probe");
    };
    check_probe(e.set, "set");
    check_probe(swept, "sweep");
    for (std::size_t c = 0; c < e.cases.size(); ++c)
      check_probe(e.cases[c], fmt::format("cases[{}]", c));
  }
}

// The index of an earlier item equal to list[k], if any.
template <class T>
std::optional<std::size_t> earlier_equal(const std::vector<T>& list, std::size_t k) {
  for (std::size_t j = 0; j < k; ++j)
    if (list[j] == list[k]) return j;
  return std::nullopt;
}

// A scene, swept value or case given twice would plan the same runs twice under one id, and the
// plan would silently hold fewer runs (and an ensemble fewer samples) than the definition lists.
void check_distinct(const JsonReader& in, const Experiment& e) {
  const std::string why = "the plan would hold the same runs twice under one id (for more "
                          "samples of one setting, use repeats)";
  std::vector<std::filesystem::path> scenes;
  for (const auto& path : e.scene_paths) {
    std::error_code ignored;  // the files exist (checked on reading); a failure keeps the path
    const auto canonical = std::filesystem::weakly_canonical(path, ignored);
    scenes.push_back(canonical.empty() ? path : canonical);
  }
  for (std::size_t k = 0; k < scenes.size(); ++k)
    if (const auto j = earlier_equal(scenes, k))
      throw in.error(fmt::format("scenes[{}]", k),
                     fmt::format("names the same file as scenes[{}]: {}", *j, why));
  for (const auto& [key, values] : e.sweep)
    for (std::size_t k = 0; k < values.size(); ++k)
      if (const auto j = earlier_equal(values, k))
        throw in.error(fmt::format("sweep.{}[{}]", key, k),
                       fmt::format("{} is also item {}: {}", quote_json(values[k]), *j, why));
  for (std::size_t k = 0; k < e.cases.size(); ++k)
    if (const auto j = earlier_equal(e.cases, k)) {
      const std::string field = fmt::format("cases[{}]", k);
      const std::string message = fmt::format("equals cases[{}]: {}", *j, why);
      if (e.cases_file.empty()) throw in.error(field, message);
      throw InputError(e.cases_file, field, message + " in " + in.file());
    }
}

// An ensemble perturbs every repeat's initial positions (docs/experiments.md, "Ensembles"): by
// 1e-3 spacing unless the experiment sets perturbation.position itself. The seed is the repeat's.
void add_ensemble_defaults(const JsonReader& in, Experiment& e) {
  auto names = [](const std::vector<Override>& list, const std::string& key) {
    return std::any_of(list.begin(), list.end(), [&](const Override& o) { return o.first == key; });
  };
  // A whole perturbation object, applied before (set) or after (sweep, cases) the ensemble's
  // own keys, would drop the default position or the repeat's seed without a word.
  const std::string whole = "perturbation";
  const std::string why = "with repeats, give perturbation.* keys one by one: a whole object "
                          "would replace the repeats' seeds or their default position";
  if (names(e.set, whole)) throw in.error("set.perturbation", why);
  for (const auto& [key, values] : e.sweep)
    if (key == whole) throw in.error("sweep.perturbation", why);
  for (std::size_t c = 0; c < e.cases.size(); ++c)
    if (names(e.cases[c], whole)) throw in.error(fmt::format("cases[{}].perturbation", c), why);
  // When some cases give their own position, the others get the default as a case value (a key
  // is in `set` or in the cases, not both); they got none, and their repeats were identical.
  const std::string key = "perturbation.position";
  bool position = names(e.set, key);
  for (const auto& [swept, values] : e.sweep) position = position || swept == key;
  const bool in_cases =
      std::any_of(e.cases.begin(), e.cases.end(), [&](const auto& c) { return names(c, key); });
  if (!position && in_cases) {
    for (auto& c : e.cases)
      if (!names(c, key)) c.emplace_back(key, 1e-3);
  } else if (!position) {
    e.set.emplace_back(key, 1e-3);
  }
  bool seeded = names(e.set, repeat_parameter);
  for (const auto& [swept, values] : e.sweep) seeded = seeded || swept == repeat_parameter;
  for (const auto& c : e.cases) seeded = seeded || names(c, repeat_parameter);
  if (seeded) throw in.error("repeats", "the repeats set perturbation.seed: do not set it too");
}

}  // namespace

// Applied in turn, the later of two overlapping paths would replace or change the earlier's
// value, so which one a run gets would depend on the order of application, not on the
// definition.
bool paths_overlap(const std::string& a, const std::string& b) {
  return a == b || holds(a, b) || holds(b, a);
}

const std::vector<std::string>& known_metrics() {
  static const std::vector<std::string> names = {"energy_drift", "vibration",   "attach_error",
                                                 "mapping_error", "work_precision", "stable_dt",
                                                 "restart_error", "snapshots"};
  return names;
}

Experiment parse_experiment(const nlohmann::json& source, const std::string& file,
                            const std::filesystem::path& base_dir) {
  JsonReader in(source, file, "");
  Experiment e;
  e.file = file;
  e.source = source;
  e.name = in.string("name");
  if (e.name.empty()) throw in.error("name", "must not be empty");
  e.question = in.string("question", "");

  const nlohmann::json& scenes = in.raw("scenes");
  if (!scenes.is_array() || scenes.empty())
    throw in.error("scenes", "expected a non-empty list of scene files");
  for (std::size_t k = 0; k < scenes.size(); ++k) {
    const std::string field = fmt::format("scenes[{}]", k);
    if (!scenes[k].is_string())
      throw in.error(field, "expected a file name, got " + quote_json(scenes[k]));
    const std::string name = scenes[k].get<std::string>();
    const std::filesystem::path path = base_dir / name;
    if (const auto reason = unreadable_file_reason(path.string()))
      throw in.error(field, "no scene file " + path.string() + ": " + *reason);
    e.scenes.push_back(name);
    e.scene_paths.push_back(path);
  }

  if (in.has("duration"))
    e.set.emplace_back("duration", in.positive("duration", in.number("duration")));
  if (in.has("set")) {
    for (auto& o : read_overrides(in, "set")) {
      if (o.first == "duration" && source.contains("duration"))
        throw in.error("set.duration", "duration is given twice");
      e.set.push_back(std::move(o));
    }
  }

  if (in.has("sweep")) {
    for (auto& [key, values] : read_overrides(in, "sweep")) {
      if (!values.is_array() || values.empty())
        throw in.error("sweep." + key, "expected a non-empty list of values");
      e.sweep.emplace_back(key, std::vector<nlohmann::json>(values.begin(), values.end()));
    }
  }
  if (in.has("cases")) std::tie(e.cases, e.cases_file) = read_cases(in, base_dir);
  if (in.has("reference")) {
    e.reference = read_overrides(in, "reference");
    if (e.reference.empty()) throw in.error("reference", "must set at least one value");
    // A reference is another method for the same problem: the report compares every run with
    // its reference particle by particle, over the same time, so nothing but the method and
    // what it writes (outputs never change the steps) may differ.
    for (const auto& [key, value] : e.reference)
      if (!paths_overlap(key, "integrator") && !paths_overlap(key, "output"))
        throw in.error("reference." + key,
                       "a reference changes only the method and its outputs (integrator.* and "
                       "output.* keys), so that it solves the runs' problem");
  }
  if (in.has("restart_error")) {
    if (e.reference.empty())
      throw in.error("restart_error", "needs a reference: the runs restart from its states");
    JsonReader restart = in.object("restart_error");
    e.restart_horizons = restart.numbers("horizons");
    if (e.restart_horizons.empty() || e.restart_horizons.size() > limits::max_restart_horizons)
      throw restart.error("horizons", fmt::format("expected 1 to {} horizons",
                                                  limits::max_restart_horizons));
    restart.finish();
  }
  if (in.has("bisect")) e.bisect = read_bisect(in.object("bisect"));

  if (in.has("metrics")) {
    const nlohmann::json& metrics = in.raw("metrics");
    if (!metrics.is_array()) throw in.error("metrics", "expected a list of metric names");
    for (std::size_t k = 0; k < metrics.size(); ++k) {
      const std::string field = fmt::format("metrics[{}]", k);
      const auto& known = known_metrics();
      if (!metrics[k].is_string() ||
          std::find(known.begin(), known.end(), metrics[k].get<std::string>()) == known.end())
        throw in.error(field, fmt::format("unknown metric {} (known: {})", quote_json(metrics[k]),
                                          fmt::join(known, ", ")));
      e.metrics.push_back(metrics[k].get<std::string>());
    }
  }
  if (in.has("repeats")) {
    e.repeats = in.integer("repeats");
    if (e.repeats < 1) throw in.error("repeats", "must be at least 1");
    add_ensemble_defaults(in, e);
  }
  in.finish();
  check_disjoint(in, e);
  check_distinct(in, e);
  check_plan_size(e);
  return e;
}

Experiment load_experiment(const std::string& file) {
  return parse_experiment(read_json_file(file), file, std::filesystem::path(file).parent_path());
}

}  // namespace drape
