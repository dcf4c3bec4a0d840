#include "experiments/cli/experiment_cli.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <iostream>

#include "core/io/input_error.hpp"
#include "core/io/output_error.hpp"
#include "experiments/options/decimal_integer.hpp"
#include "experiments/options/threads_option.hpp"
#include "experiments/sweep/experiment.hpp"
#include "experiments/sweep/experiment_folder.hpp"
#include "experiments/sweep/experiment_merge.hpp"
#include "experiments/sweep/experiment_runner.hpp"
#include "experiments/sweep/run_validation.hpp"

namespace drape {

namespace fs = std::filesystem;

namespace {

// Runs a program with arguments (no shell, so paths need no quoting); returns its exit status.
int run_program(const std::vector<std::string>& argv) {
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  std::cout.flush();
  std::cerr.flush();
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error("cannot start " + argv.front());
  if (pid == 0) {
    ::execv(args[0], args.data());
    _exit(127);
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) throw std::runtime_error("cannot wait for " + argv.front());
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

std::string python_interpreter() {
  const char* env = std::getenv("DRAPE_PYTHON");
  return env && *env ? env : DRAPE_PYTHON;
}

}  // namespace

int experiment_command(const std::string& file, const std::string& out_dir, int jobs, int threads,
                       const std::string& shard, bool list_only, bool progress, bool overwrite) {
  const Experiment experiment = load_experiment(file);
  if (!list_only) check_experiment_folder(out_dir, experiment.name, overwrite);
  ExperimentOptions options;
  options.out_dir = out_dir;
  options.overwrite = overwrite;
  options.jobs = jobs;
  options.threads = threads;
  if (!shard.empty()) options.shard = parse_shard(shard);
  options.progress = progress;
  options.terminal = ::isatty(2) != 0;
  if (list_only) {
    std::vector<RunSpec> listed;
    for (const RunSpec& run : expand_runs(experiment))
      if (!options.shard || options.shard->contains(run.index)) listed.push_back(run);
    validate_runs(experiment, listed);  // a plan that cannot run is not listed as if it could
    for (const RunSpec& run : listed) {
      std::string params;
      for (const auto& [key, value] : run.parameters) params += " " + key + "=" + value.dump();
      fmt::print("{:>5} {} {}{}\n", run.index, run.id, run.scene, params);
    }
    return 0;
  }
  const ExperimentTally t = run_experiment(experiment, options);
  std::cerr << fmt::format("drapelab: {}: {} runs{}: {}\n", experiment.name, t.planned,
                           options.shard ? " in shard " + shard : "", t.summary());
  return t.errors + t.crashed > 0 ? 1 : 0;
}

int merge_command(const std::string& out_dir, const std::vector<std::string>& sources) {
  // A folder merge cannot write its results in (each goes to a new file, renamed) is named
  // before any run is copied (exit 2), not found by the last write (exit 4).
  std::error_code ec;
  const fs::path probe =
      fs::path(out_dir) / (".drapelab-write-probe-" + std::to_string(::getpid()));
  if (fs::is_directory(out_dir, ec))
    if (const auto reason = open_for_writing_reason(probe.string()))
      throw InputError(out_dir, "", *reason);
  const std::vector<fs::path> paths(sources.begin(), sources.end());
  const std::vector<std::string> missing = merge_results(out_dir, paths);
  if (missing.empty()) return 0;
  std::cerr << fmt::format("drapelab: merge: {} runs have no result yet:\n", missing.size());
  for (const auto& id : missing) std::cerr << "  " << id << "\n";
  return 1;
}

int report_command(const std::string& dir, const std::vector<std::string>& extra_args) {
  const std::string python = python_interpreter();
  const fs::path script = fs::path(DRAPE_SOURCE_DIR) / "analysis" / "report.py";
  if (!fs::is_regular_file(script))
    throw std::runtime_error("cannot find " + script.string() + " (the source tree moved?)");
  if (::access(python.c_str(), X_OK) != 0 ||
      run_program({python, "-c", "import matplotlib, numpy"}) != 0) {
    std::cerr << "drapelab: report needs " << python
              << " with matplotlib and numpy (Debian: apt install python3-matplotlib "
                 "python3-numpy); set DRAPE_PYTHON to use another interpreter\n";
    return 1;
  }
  // The script writes the report's 3-D viewer pages with this very program's `view`.
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  std::vector<std::string> argv = {python, script.string(), dir};
  if (!ec) argv.insert(argv.end(), {"--drapelab", self.string()});
  argv.insert(argv.end(), extra_args.begin(), extra_args.end());
  return run_program(argv);
}

ExperimentCommands::ExperimentCommands(CLI::App& app) {
  m_experiment = app.add_subcommand(
      "experiment", "run an experiment's plan in parallel, resumably, into --out DIR");
  m_experiment->add_option("file", m_file, "experiment JSON file")->required();
  m_experiment->add_option("--out", m_out, "output folder")->required();
  // Each job is a child process: beyond 1024 at once a large plan would exhaust the machine's
  // processes and memory, not run faster.
  m_experiment->add_option("--jobs,-j", m_jobs, "parallel runs, at most 1024 (default: all cores)")
      ->transform(decimal_integer())
      ->check(CLI::Range(0, 1024));
  add_threads_option(*m_experiment, m_threads, "all cores / --jobs, at least 1, for each run");
  m_experiment
      ->add_option("--shard", m_shard,
                   "run only the K-th of N slices (1-based K/N), then `drapelab merge`")
      ->check(CLI::Validator(
          [](const std::string& value) {
            return value.empty() ? std::string("expected K/N, got an empty value") : std::string();
          },
          "K/N"));
  m_experiment->add_flag("--list", m_list, "print the plan (index, run id, values) and stop");
  m_experiment->add_flag("--overwrite", m_overwrite,
                         "replace a run's or another experiment's files in --out (resume is lost)");
  m_experiment->add_flag("--no-progress", m_no_progress, "no progress display (on a terminal) or per-run lines (otherwise)");
  m_experiment->footer(
      "Examples:\n"
      "  drapelab experiment experiments/definitions/integrator_comparison.json --out out/ic\n"
      "  drapelab experiment experiments/definitions/vibration.json --out out/vib --list\n"
      "  drapelab experiment experiments/definitions/vibration.json --out out/vib --shard 1/4 -j 2");

  m_merge = app.add_subcommand("merge", "join the runs of shards into DIR/results.{csv,json}");
  m_merge->add_option("dir", m_out, "experiment output folder to complete")->required();
  m_merge->add_option("sources", m_sources, "other output folders of the same experiment");
  m_merge->footer("Example:\n  drapelab merge out/vib machine2/out/vib machine3/out/vib");

  m_report = app.add_subcommand("report", "plots and report.html of an experiment folder");
  m_report->add_option("dir", m_out, "experiment output folder")->required();
  m_report->footer("Example:\n  drapelab report out/integrator_comparison");
  m_report->allow_extras();  // everything after DIR goes to analysis/report.py
}

int ExperimentCommands::dispatch() const {
  if (m_experiment->parsed())
    return experiment_command(m_file, m_out, m_jobs, m_threads, m_shard, m_list, !m_no_progress,
                              m_overwrite);
  if (m_merge->parsed()) return merge_command(m_out, m_sources);
  if (m_report->parsed()) {
    return report_command(m_out, m_report->remaining());
  }
  return -1;
}

}  // namespace drape
