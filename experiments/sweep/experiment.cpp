#include "experiments/sweep/experiment.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <set>
#include <tuple>
#include <utility>

#include "core/scene/input_error.hpp"
#include "core/scene/json_reader.hpp"
#include "core/scene/scene.hpp"
#include "experiments/sweep/ensemble_summary.hpp"
#include "experiments/sweep/plan_size.hpp"
#include "core/scene/json_text.hpp"

namespace drape {

namespace {

// A scene path must be something load_scene's apply_override accepts: dotted, no empty part.
void check_key(const JsonReader& in, const std::string& field, const std::string& key) {
  if (key.empty() || key.front() == '.' || key.back() == '.' || key.find("..") != std::string::npos ||
      key.find('=') != std::string::npos)
    throw in.error(field, "'" + key + "' is not a scene path like integrator.dt");
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

// A case key that also appears in the sweep or in `set` would make the run ambiguous.
void check_disjoint(const JsonReader& in, const Experiment& e) {
  std::set<std::string> swept;
  for (const auto& [key, values] : e.sweep) swept.insert(key);
  for (const auto& [key, value] : e.set)
    if (swept.count(key)) throw in.error("set." + key, "is also swept");
  // A clash in a shared cases file names that file's field and the definition.
  auto clash = [&](std::size_t c, const std::string& key, const std::string& what) {
    const std::string field = fmt::format("cases[{}].{}", c, key);
    if (e.cases_file.empty()) return in.error(field, what);
    return InputError(e.cases_file, field, what + " in " + in.file());
  };
  for (std::size_t c = 0; c < e.cases.size(); ++c)
    for (const auto& [key, value] : e.cases[c]) {
      if (swept.count(key)) throw clash(c, key, "is also swept");
      for (const auto& [set_key, set_value] : e.set)
        if (set_key == key) throw clash(c, key, "is also in set");
    }
  if (e.bisect) {
    const std::string& p = e.bisect->parameter;
    if (swept.count(p)) throw in.error("bisect.parameter", "'" + p + "' is also swept");
    for (const auto& c : e.cases)
      for (const auto& [key, value] : c)
        if (key == p) throw in.error("bisect.parameter", "'" + p + "' is also set by a case");
  }
}

// An ensemble perturbs every repeat's initial positions (docs/experiments.md, "Ensembles"): by
// 1e-3 spacing unless the experiment sets perturbation.position itself. The seed is the repeat's.
void add_ensemble_defaults(const JsonReader& in, Experiment& e) {
  auto names = [](const std::vector<Override>& list, const std::string& key) {
    return std::any_of(list.begin(), list.end(), [&](const Override& o) { return o.first == key; });
  };
  bool position = names(e.set, "perturbation.position");
  for (const auto& [key, values] : e.sweep) position = position || key == "perturbation.position";
  for (const auto& c : e.cases) position = position || names(c, "perturbation.position");
  if (!position) e.set.emplace_back("perturbation.position", 1e-3);
  bool seeded = names(e.set, repeat_parameter);
  for (const auto& [key, values] : e.sweep) seeded = seeded || key == repeat_parameter;
  for (const auto& c : e.cases) seeded = seeded || names(c, repeat_parameter);
  if (seeded) throw in.error("repeats", "the repeats set perturbation.seed: do not set it too");
}

std::uint64_t fnv1a(const std::string& text) {
  std::uint64_t h = 1469598103934665603ULL;
  for (const unsigned char ch : text) {
    h ^= ch;
    h *= 1099511628211ULL;
  }
  return h;
}

std::string slug_part(const nlohmann::json& value) {
  std::string text = value.is_string() ? value.get<std::string>() : value.dump();
  for (char& ch : text)
    if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '.' || ch == '-' || ch == '+'))
      ch = '_';
  return text;
}

void append_run(std::vector<RunSpec>& plan, std::set<std::string>& ids, RunSpec run) {
  run.id = run_id(run);
  if (!ids.insert(run.id).second) return;  // a reference shared by several runs
  run.index = static_cast<int>(plan.size());
  plan.push_back(std::move(run));
}

}  // namespace

std::vector<std::string> RunSpec::assignments() const {
  std::vector<std::string> out;
  for (const auto& [key, value] : overrides) out.push_back(key + "=" + value.dump());
  return out;
}

nlohmann::json RunSpec::to_json() const {
  nlohmann::json params = nlohmann::json::object();
  for (const auto& [key, value] : parameters) params[key] = value;
  nlohmann::json j = {{"id", id},
                      {"index", index},
                      {"scene", scene},
                      {"parameters", params},
                      {"overrides", assignments()},
                      {"reference", reference},
                      {"is_reference", is_reference}};
  if (bisect) {
    j["bisect"] = {{"parameter", bisect->parameter}, {"low", bisect->low},
                   {"high", bisect->high}, {"steps", bisect->steps}};
    if (bisect->max_drift) j["bisect"]["max_drift"] = *bisect->max_drift;
    if (bisect->max_rise) j["bisect"]["max_rise"] = *bisect->max_rise;
  }
  return j;
}

std::string Shard::tag() const { return fmt::format("{}-of-{}", index, count); }

const std::vector<std::string>& known_metrics() {
  static const std::vector<std::string> names = {"energy_drift", "vibration",   "attach_error",
                                                 "mapping_error", "work_precision", "stable_dt",
                                                 "restart_error", "snapshots"};
  return names;
}

std::string run_id(const RunSpec& run) {
  nlohmann::json identity = run.to_json();
  // The id must not depend on where the run sits in the plan, nor on itself.
  identity.erase("id");
  identity.erase("index");
  identity.erase("reference");
  std::string slug = std::filesystem::path(run.scene).stem().string();
  if (run.is_reference) slug += "-reference";
  if (run.bisect) slug += "-bisect";
  for (const auto& [key, value] : run.parameters) slug += "-" + slug_part(value);
  if (slug.size() > 72) slug.resize(72);
  return fmt::format("{}-{:08x}", slug, fnv1a(identity.dump()) & 0xffffffffULL);
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
    if (!std::filesystem::is_regular_file(path))
      throw in.error(field, "no scene file " + path.string());
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
    // The report compares every run with its reference particle by particle.
    for (const auto& [key, value] : e.reference)
      if (key == "cloth" || key == "cloth.rows" || key == "cloth.cols")
        throw in.error("reference." + key, "the reference must keep the runs' grid");
  }
  if (in.has("restart_error")) {
    if (e.reference.empty())
      throw in.error("restart_error", "needs a reference: the runs restart from its states");
    JsonReader restart = in.object("restart_error");
    e.restart_horizons = restart.numbers("horizons");
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
  check_plan_size(e);
  return e;
}

Experiment load_experiment(const std::string& file) {
  return parse_experiment(read_json_file(file), file, std::filesystem::path(file).parent_path());
}

namespace {

// Adds a run and, when the experiment has one, its reference run.
void plan_run(const Experiment& e, RunSpec run, std::vector<RunSpec>& plan,
              std::set<std::string>& ids, std::vector<RunSpec>& references) {
  if (!e.reference.empty()) {
    // The reference shares the scene and every non-integrator value, solved with the
    // reference's method, so that the difference is the integrator's error alone.
    RunSpec ref;
    ref.scene = run.scene;
    ref.scene_path = run.scene_path;
    ref.is_reference = true;
    for (const auto& p : run.parameters)
      if (p.first.rfind("integrator.", 0) != 0) ref.parameters.push_back(p);
    ref.parameters.insert(ref.parameters.end(), e.reference.begin(), e.reference.end());
    ref.overrides = e.set;
    ref.overrides.insert(ref.overrides.end(), ref.parameters.begin(), ref.parameters.end());
    ref.id = run_id(ref);
    run.reference = ref.id;
    // The restart error's reference is the reference run's integrator, as its scene reads it
    // (scene.md, restart_error); its horizons are checked with the run's scene.
    if (!e.restart_horizons.empty()) {
      const Scene ref_scene = load_scene(ref.scene_path.string(), ref.assignments());
      run.overrides.emplace_back("restart_error",
                                 nlohmann::json{{"reference", ref_scene.integrator},
                                                {"horizons", e.restart_horizons}});
    }
    references.push_back(std::move(ref));
  }
  append_run(plan, ids, std::move(run));
}

}  // namespace

std::vector<RunSpec> expand_runs(const Experiment& e) {
  // Every combination of the swept values, the first key varying slowest.
  std::vector<std::vector<Override>> combos = {{}};
  for (const auto& [key, values] : e.sweep) {
    std::vector<std::vector<Override>> next;
    for (const auto& combo : combos)
      for (const auto& value : values) {
        next.push_back(combo);
        next.back().emplace_back(key, value);
      }
    combos = std::move(next);
  }
  const std::vector<std::vector<Override>> cases =
      e.cases.empty() ? std::vector<std::vector<Override>>{{}} : e.cases;

  std::vector<RunSpec> plan;
  std::vector<RunSpec> references;
  std::set<std::string> ids;
  for (std::size_t s = 0; s < e.scenes.size(); ++s)
    for (const auto& one_case : cases)
      for (const auto& combo : combos) {
        RunSpec run;
        run.scene = e.scenes[s];
        run.scene_path = e.scene_paths[s];
        run.parameters = one_case;
        run.parameters.insert(run.parameters.end(), combo.begin(), combo.end());
        run.overrides = e.set;
        run.overrides.insert(run.overrides.end(), run.parameters.begin(), run.parameters.end());
        run.bisect = e.bisect;
        if (e.repeats == 0) plan_run(e, std::move(run), plan, ids, references);
        // An ensemble: the repeats of one group differ only in their perturbation seed.
        for (int r = 1; r <= e.repeats; ++r) {
          RunSpec repeat = run;
          repeat.parameters.emplace_back(repeat_parameter, r);
          repeat.overrides.emplace_back(repeat_parameter, r);
          plan_run(e, std::move(repeat), plan, ids, references);
        }
      }
  for (auto& ref : references) append_run(plan, ids, std::move(ref));
  return plan;
}

Shard parse_shard(const std::string& text) {
  const auto slash = text.find('/');
  int k = 0, n = 0;
  try {
    std::size_t used_k = 0, used_n = 0;
    if (slash == std::string::npos) throw std::invalid_argument("no slash");
    k = std::stoi(text.substr(0, slash), &used_k);
    n = std::stoi(text.substr(slash + 1), &used_n);
    if (used_k != slash || used_n != text.size() - slash - 1) throw std::invalid_argument("junk");
  } catch (const std::exception&) {
    throw InputError("--shard", "", "expected K/N with 1 <= K <= N, got '" + text + "'");
  }
  if (n < 1 || k < 1 || k > n)
    throw InputError("--shard", "", "expected K/N with 1 <= K <= N, got '" + text + "'");
  return {k, n};
}

}  // namespace drape
