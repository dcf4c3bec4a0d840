#include "experiments/sweep/experiment_runner.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <functional>
#include <iostream>
#include <set>
#include <thread>

#include "core/io/input_error.hpp"
#include "core/io/json_reader.hpp"
#include "core/scene/scene.hpp"
#include "experiments/sweep/child_runs.hpp"
#include "experiments/sweep/experiment_folder.hpp"
#include "experiments/sweep/progress_reporter.hpp"
#include "experiments/sweep/ensemble_summary.hpp"
#include "experiments/sweep/results_table.hpp"
#include "experiments/sweep/run_progress_file.hpp"
#include "experiments/sweep/stored_runs.hpp"
#include "experiments/sweep/run_validation.hpp"
#include "experiments/sweep/deliberate_crash.hpp"
#include "experiments/output/run_files.hpp"
#include "core/parallel/parallel_for.hpp"
#include "experiments/runner/run_scene.hpp"

namespace drape {

namespace fs = std::filesystem;

namespace {

// The row of a run finished earlier, or nothing when it must run (again): a run that could not
// run or crashed is retried, in case the cause (a full disk, a bug since fixed) is gone.
std::optional<nlohmann::json> finished_row(const RunSpec& run, const fs::path& dir) {
  auto row = finished_run(dir, run.to_json()).row;
  if (!row) return std::nullopt;
  const std::string status = row->value("status", "error");
  if (status == "error" || status == "crashed") return std::nullopt;
  (*row)["index"] = run.index;
  (*row)["reference"] = run.reference;
  return row;
}

// Largest stable value of one parameter, by bisection (geometric: step sizes span decades).
nlohmann::json run_bisect(const RunSpec& run, const fs::path& dir, RunProgressFile& progress) {
  const BisectSpec& b = *run.bisect;
  nlohmann::json probes = nlohmann::json::array();
  nlohmann::json last_stable_summary;
  double wall = 0.0, cpu = 0.0;
  auto probe = [&](double value) {
    const Scene scene = load_scene(run.scene_path.string(), run.assignments(value));
    // At most low, high and `steps` probes; fewer when the bracket is found wrong at once.
    progress.set_part(static_cast<int>(probes.size()), b.steps + 2);
    const RunOutcome o =
        run_scene(scene, dir / experiment_run_file::probes / fmt::format("{:02d}", probes.size()), &progress);
    const double drift = o.summary.value("energy_drift_max_rel", 0.0);
    const double rise = o.summary.value("energy_rise_max_rel", 0.0);
    const bool stable = o.status == "ok" && (!b.max_drift || drift <= *b.max_drift) &&
                        (!b.max_rise || rise <= *b.max_rise);
    wall += o.summary.value("wall_seconds", 0.0);
    cpu += o.summary.value("cpu_seconds", 0.0);
    probes.push_back({{"value", value}, {"status", o.status}, {"stable", stable},
                      {"energy_drift_max_rel", drift}, {"energy_rise_max_rel", rise}});
    if (stable) last_stable_summary = o.summary;
    return stable;
  };
  double lo = b.low, hi = b.high;
  std::string status = "ok", reason;
  nlohmann::json stable_value, unstable_value;
  if (!probe(lo)) {
    status = "failed";
    reason = fmt::format("bisect.low = {} is already unstable", lo);
    unstable_value = lo;
  } else if (probe(hi)) {
    reason = fmt::format("bisect.high = {} is still stable", hi);
    stable_value = hi;
  } else {
    for (int s = 0; s < b.steps; ++s) {
      const double mid = std::sqrt(lo * hi);
      (probe(mid) ? lo : hi) = mid;
    }
    stable_value = lo;
    unstable_value = hi;
  }
  nlohmann::json summary = last_stable_summary.is_null() ? nlohmann::json::object() : last_stable_summary;
  summary["status"] = status;
  summary["reason"] = reason;
  summary["wall_seconds"] = wall;
  summary["cpu_seconds"] = cpu;
  write_json(dir / experiment_run_file::bisection, {{"parameter", b.parameter}, {"stable_value", stable_value},
                                          {"unstable_value", unstable_value}, {"probes", probes}});
  nlohmann::json row = result_row(run, summary);
  row["bisect_parameter"] = b.parameter;
  row["stable_value"] = stable_value;
  row["unstable_value"] = unstable_value;
  row["probes"] = probes.size();
  return row;
}

// Runs one plan entry in its own folder and writes its result.json; never throws (a failure is
// the run's status). Runs in a child process (run_experiment), which tells the parent its
// progress through the folder's progress.json, removed once the run ends.
void execute_run(const RunSpec& run, const fs::path& dir) {
  RunProgressFile progress(dir);
  nlohmann::json row;
  try {
    fs::remove_all(dir);  // leftovers of an interrupted run would mix with the new files
    fs::create_directories(dir);
    write_json(dir / experiment_run_file::identity, run_identity(run.to_json()));
    crash_if_asked_for_test(run.id);
    if (run.bisect) {
      row = run_bisect(run, dir, progress);
    } else {
      const Scene scene = load_scene(run.scene_path.string(), run.assignments());
      row = result_row(run, run_scene(scene, dir, &progress).summary);
    }
  } catch (const std::exception& e) {
    row = error_row(run, e.what());
  }
  try {
    fs::remove(progress_file(dir));
    write_json(dir / experiment_run_file::result, row);
  } catch (const std::exception& e) {
    std::cerr << "drapelab: " << run.id << ": " << e.what() << "\n";
  }
}

// The row of a run whose child ended: its result.json, or a crashed row the parent writes in
// its place when the child died before writing one (or exited without a result).
nlohmann::json ended_row(const RunSpec& run, const fs::path& dir, const ChildEnd& end) {
  if (end.ok()) {
    if (auto row = read_json_if_present(dir / experiment_run_file::result)) return *row;
  }
  nlohmann::json row = error_row(run, describe_child_end(end));
  row["status"] = "crashed";
  try {
    fs::create_directories(dir);
    write_json(dir / experiment_run_file::result, row);
  } catch (const std::exception&) {
    // The row still reaches the results table; resume reruns the run either way.
  }
  return row;
}

std::vector<std::string> parameter_keys(const std::vector<RunSpec>& plan) {
  std::vector<std::string> keys;
  for (const RunSpec& run : plan)
    for (const auto& [key, value] : run.parameters)
      if (std::find(keys.begin(), keys.end(), key) == keys.end()) keys.push_back(key);
  return keys;
}

nlohmann::json experiment_header(const Experiment& e, const std::vector<RunSpec>& plan) {
  nlohmann::json runs = nlohmann::json::array();
  for (const RunSpec& run : plan) runs.push_back(run.to_json());
  return {{"name", e.name},           {"question", e.question},
          {"file", e.file},           {"metrics", e.metrics},
          {"parameters", parameter_keys(plan)}, {"plan_size", plan.size()},
          {"experiment", e.source},   {"plan", runs}};
}

}  // namespace

ExperimentTally run_experiment(const Experiment& experiment, const ExperimentOptions& options) {
  const std::vector<RunSpec> plan = expand_runs(experiment);
  std::vector<const RunSpec*> slice;
  for (const RunSpec& run : plan)
    if (!options.shard || options.shard->contains(run.index)) slice.push_back(&run);
  {
    std::vector<RunSpec> to_check;
    for (const RunSpec* run : slice) to_check.push_back(*run);
    validate_runs(experiment, to_check);
  }
  if (options.overwrite) clear_experiment_folder(options.out_dir);

  fs::create_directories(options.out_dir / "runs");
  const nlohmann::json header = experiment_header(experiment, plan);
  write_json(options.out_dir / "experiment.json", header, process_tmp_suffix());
  // A shard writes its own table under shards/; the merged one is merge's to replace.
  if (!options.shard) remove_results_table(options.out_dir);

  std::vector<nlohmann::json> rows(slice.size());
  // It counts the runs too: its tally is the invocation's.
  ProgressReporter progress(static_cast<int>(slice.size()),
                            !options.progress  ? ProgressStyle::Off
                            : options.terminal ? ProgressStyle::Terminal
                                               : ProgressStyle::Lines,
                            std::cerr);
  // Finished runs are read here; the others run each in a child process, so that a crash, an
  // abort or the out-of-memory killer ends one run, not the experiment.
  std::vector<std::size_t> pending;
  for (std::size_t k = 0; k < slice.size(); ++k) {
    if (auto row = finished_row(*slice[k], options.out_dir / "runs" / slice[k]->id)) {
      progress.run_finished(slice[k]->id, row->value("status", "error"), true);
      rows[k] = std::move(*row);
    } else {
      pending.push_back(k);
    }
  }
  const unsigned hardware = std::max(1u, std::thread::hardware_concurrency());
  const std::size_t jobs = options.jobs > 0 ? options.jobs : hardware;
  // The runs together use the cores once over: the machine is not oversubscribed.
  const int run_threads =
      options.threads > 0 ? options.threads : static_cast<int>(std::max<std::size_t>(1, hardware / jobs));
  auto dir_of = [&](std::size_t p) { return options.out_dir / "runs" / slice[pending[p]]->id; };
  // On a terminal the block is redrawn on a timer with each running child's progress.json.
  std::set<std::size_t> running;
  std::function<void()> tick;
  if (options.progress && options.terminal)
    tick = [&] {
      for (const std::size_t p : running)
        if (const auto fraction = read_run_progress(dir_of(p)))
          progress.run_progress(slice[pending[p]]->id, *fraction);
      progress.redraw();
    };
  run_in_children(
      pending.size(), jobs,
      [&](std::size_t p) {
        set_thread_count(run_threads);
        execute_run(*slice[pending[p]], dir_of(p));
        return 0;
      },
      [&](std::size_t p, const ChildEnd& end) {
        running.erase(p);
        nlohmann::json row = ended_row(*slice[pending[p]], dir_of(p), end);
        const std::string status = row.value("status", "error");
        progress.run_finished(slice[pending[p]]->id, status, false);
        rows[pending[p]] = std::move(row);
      },
      [&](std::size_t p) {
        running.insert(p);
        progress.run_started(slice[pending[p]]->id);
      },
      tick);
  progress.finish();

  if (options.shard) {
    fs::create_directories(options.out_dir / "shards");
    write_results_table(options.out_dir / "shards" / options.shard->tag(), header, rows,
                fmt::format("{}/{}", options.shard->index, options.shard->count));
  } else {
    write_results_table(options.out_dir / "results", header, rows, "");
  }
  return progress.tally();
}

}  // namespace drape
