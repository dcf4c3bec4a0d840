#pragma once
// A running run's progress as a file in its folder, progress.json (docs/experiments.md,
// "Parallel runs, progress, resume"): each run is a child process, which writes it; the parent's
// progress display reads it on its timer. No pipe to keep open, nothing shared but the folder.
#include <filesystem>
#include <optional>

#include "experiments/run/simulation.hpp"

namespace drape {

/// progress.json in a run folder.
std::filesystem::path progress_file(const std::filesystem::path& run_dir);
/// The fraction in run_dir's progress.json, or nothing when there is none (yet) or it is not
/// a progress file.
std::optional<double> read_run_progress(const std::filesystem::path& run_dir);

/// Writes a simulation's progress to progress.json, whenever it grew by 1 % or more: the run's
/// simulated time over its duration, or, for a run made of several simulations (the probes of a
/// bisection), (part + that fraction) / parts.
class RunProgressFile : public SimulationObserver {
 public:
  explicit RunProgressFile(std::filesystem::path run_dir) : m_dir(std::move(run_dir)) {}
  /// The simulations that follow are part `part` (0-based) of `parts`.
  void set_part(int part, int parts);
  void on_start(const Simulation& simulation) override { report(simulation); }
  void on_step(const Simulation& simulation, bool /*event*/) override { report(simulation); }
  /// The run's fraction from one simulation's (clamped to [0, 1]).
  double run_fraction(double simulation_fraction) const;

 private:
  void report(const Simulation& simulation);
  std::filesystem::path m_dir;
  int m_part = 0, m_parts = 1;
  double m_written = -1.0;
};

}  // namespace drape
