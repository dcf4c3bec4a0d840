#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <fstream>
#include <string_view>
#include <map>
#include <set>
#include <stdexcept>
#include <utility>
#include <vector>

#include "core/dummy/dummy_sources.hpp"
#include "core/io/input_error.hpp"
#include "core/io/json_reader.hpp"
#include "core/scene/scene.hpp"
#include "experiments/sweep/ensemble_summary.hpp"
#include "experiments/sweep/experiment.hpp"

// The plan of an experiment: its runs (every scene x case x swept combination x repeat, and the
// references), their stable ids, and the shards that split them (docs/experiments.md).
namespace drape {

namespace {

// FNV-1a of `text`, continuing from `h` (so that a file can be hashed a buffer at a time).
std::uint64_t fnv1a(std::string_view text, std::uint64_t h = 1469598103934665603ULL) {
  for (const unsigned char ch : text) {
    h ^= ch;
    h *= 1099511628211ULL;
  }
  return h;
}

// A run id's readable part before its hash: a scene's name and five values fit (a folder name
// may have 255 bytes; at 72 the main job's ids lost their table's end and their seed).
constexpr std::size_t max_slug_bytes = 120;

// One value's part of a run id, readable without the plan: a word as it is (SUNDIALS' table
// names without the "ARKODE_" that all of them share), a flag as its key or "no-" and its key,
// a number after its key ("dt0.0005", "seed2"); the key is the last part of its dotted name.
std::string slug_part(const std::string& key, const nlohmann::json& value) {
  const std::string label = key.substr(key.rfind('.') + 1);
  std::string text;
  if (value.is_string()) {
    text = value.get<std::string>();
    constexpr std::string_view arkode = "ARKODE_";
    if (text.rfind(arkode, 0) == 0 && text.size() > arkode.size()) text.erase(0, arkode.size());
  } else if (value.is_boolean()) {
    text = value.get<bool>() ? label : "no-" + label;
  } else {
    text = label + value.dump();
  }
  for (char& ch : text)
    if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '.' || ch == '-' || ch == '+'))
      ch = '_';
  return text;
}

// Read a buffer at a time: a recording may be larger than the memory a plan should take.
std::string file_digest(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::vector<char> buffer(std::size_t{1} << 16);
  std::uint64_t h = fnv1a({});
  while (in.read(buffer.data(), static_cast<std::streamsize>(buffer.size())) || in.gcount() > 0)
    h = fnv1a({buffer.data(), static_cast<std::size_t>(in.gcount())}, h);
  return fmt::format("{:016x}", h);
}

// The digests of the files a run's scene names (RunSpec::file_digests), each scene and file read
// once per plan. A scene or override that does not parse, or a file that is not a readable regular file,
// gives no digest: the plan's check (validate_runs) then names the field.
class FileDigests {
 public:
  nlohmann::json of(const RunSpec& run) {
    nlohmann::json digests = nlohmann::json::object();
    try {
      const std::string scene_file = run.scene_path.string();
      auto known_scene = m_scenes.find(scene_file);
      if (known_scene == m_scenes.end())
        known_scene = m_scenes.emplace(scene_file, read_json_file(scene_file)).first;
      nlohmann::json scene = known_scene->second;
      for (const std::string& assignment : run.assignments()) apply_override(scene, assignment);
      const std::filesystem::path base_dir = run.scene_path.parent_path();
      std::vector<std::pair<std::string, std::filesystem::path>> files;
      if (scene.contains("dummy"))
        for (const auto& [key, path] : dummy_file_paths(scene["dummy"], base_dir))
          files.emplace_back("dummy." + key, path);
      if (scene.contains("input") && scene["input"].is_object() &&
          scene["input"].contains("recording") && scene["input"]["recording"].is_string()) {
        const std::filesystem::path name = scene["input"]["recording"].get<std::string>();
        files.emplace_back("input.recording", name.is_relative() ? base_dir / name : name);
      }
      for (const auto& [field, path] : files) {
        std::error_code error;
        if (!std::filesystem::is_regular_file(path, error)) continue;
        const std::string key = path.lexically_normal().string();
        auto it = m_known.find(key);
        if (it == m_known.end()) it = m_known.emplace(key, file_digest(path)).first;
        digests[field] = it->second;
      }
    } catch (const std::exception&) {
      // left to validate_runs, which names the file and the field
    }
    return digests;
  }

 private:
  std::map<std::string, nlohmann::json> m_scenes;
  std::map<std::string, std::string> m_known;
};

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

std::vector<std::string> RunSpec::assignments(double probe) const {
  std::vector<std::string> out = assignments();
  out.push_back(bisect->parameter + "=" + nlohmann::json(probe).dump());
  return out;
}

nlohmann::json RunSpec::to_json() const {
  nlohmann::json params = nlohmann::json::object();
  for (const auto& [key, value] : parameters) params[key] = value;
  nlohmann::json j = {{"id", id},
                      {"index", index},
                      {"scene", scene},
                      {"scene_digest", scene_digest},
                      {"parameters", params},
                      {"overrides", assignments()},
                      {"reference", reference},
                      {"is_reference", is_reference}};
  if (!file_digests.empty()) j["file_digests"] = file_digests;
  if (bisect) {
    j["bisect"] = {{"parameter", bisect->parameter}, {"low", bisect->low},
                   {"high", bisect->high}, {"steps", bisect->steps}};
    if (bisect->max_drift) j["bisect"]["max_drift"] = *bisect->max_drift;
    if (bisect->max_rise) j["bisect"]["max_rise"] = *bisect->max_rise;
  }
  return j;
}

std::string Shard::tag() const { return fmt::format("{}-of-{}", index, count); }

std::string run_id(const RunSpec& run) {
  nlohmann::json identity = run.to_json();
  // The id must not depend on where the run sits in the plan, nor on itself.
  identity.erase("id");
  identity.erase("index");
  identity.erase("reference");
  std::string slug = std::filesystem::path(run.scene).stem().string();
  if (run.is_reference) slug += "-reference";
  if (run.bisect) slug += "-bisect";
  for (const auto& [key, value] : run.parameters) slug += "-" + slug_part(key, value);
  // Cut at a character's start: half a UTF-8 sequence in the id would not survive a round trip
  // through run.json (its bytes replaced), so resume and merge would never find the run again.
  if (slug.size() > max_slug_bytes) {
    std::size_t end = max_slug_bytes;
    while (end > 0 && (static_cast<unsigned char>(slug[end]) & 0xC0) == 0x80) --end;
    slug.resize(end);
  }
  return fmt::format("{}-{:08x}", slug, fnv1a(identity.dump()) & 0xffffffffULL);
}

namespace {

// Adds a run and, when the experiment has one, its reference run.
void plan_run(const Experiment& e, RunSpec run, std::vector<RunSpec>& plan,
              std::set<std::string>& ids, std::vector<RunSpec>& references, FileDigests& files) {
  if (!e.reference.empty()) {
    // The reference shares the scene and every non-integrator value, solved with the
    // reference's method, so that the difference is the integrator's error alone. A run's
    // `integrator` given whole is the run's method too: the reference inherited all of it (a
    // table, a tolerance) under its own keys.
    RunSpec ref;
    ref.scene = run.scene;
    ref.scene_path = run.scene_path;
    ref.scene_digest = run.scene_digest;
    ref.is_reference = true;
    for (const auto& p : run.parameters)
      if (!paths_overlap(p.first, "integrator")) ref.parameters.push_back(p);
    ref.parameters.insert(ref.parameters.end(), e.reference.begin(), e.reference.end());
    ref.overrides = e.set;
    ref.overrides.insert(ref.overrides.end(), ref.parameters.begin(), ref.parameters.end());
    ref.file_digests = files.of(ref);
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
  std::vector<std::string> digests;
  for (const auto& path : e.scene_paths) digests.push_back(file_digest(path));
  FileDigests files;
  for (std::size_t s = 0; s < e.scenes.size(); ++s)
    for (const auto& one_case : cases)
      for (const auto& combo : combos) {
        RunSpec run;
        run.scene = e.scenes[s];
        run.scene_path = e.scene_paths[s];
        run.scene_digest = digests[s];
        run.parameters = one_case;
        run.parameters.insert(run.parameters.end(), combo.begin(), combo.end());
        run.overrides = e.set;
        run.overrides.insert(run.overrides.end(), run.parameters.begin(), run.parameters.end());
        run.bisect = e.bisect;
        run.file_digests = files.of(run);
        if (e.repeats == 0) plan_run(e, std::move(run), plan, ids, references, files);
        // An ensemble: the repeats of one group differ only in their perturbation seed.
        for (int r = 1; r <= e.repeats; ++r) {
          RunSpec repeat = run;
          repeat.parameters.emplace_back(repeat_parameter, r);
          repeat.overrides.emplace_back(repeat_parameter, r);
          plan_run(e, std::move(repeat), plan, ids, references, files);
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
    // Digits only, without a leading zero: stoi would also take "+1", " 1" and "01".
    const auto plain = [](const std::string& part) {
      return !part.empty() && part[0] != '0' &&
             std::all_of(part.begin(), part.end(), [](char c) { return c >= '0' && c <= '9'; });
    };
    if (!plain(text.substr(0, slash)) || !plain(text.substr(slash + 1)))
      throw std::invalid_argument("not K/N");
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
