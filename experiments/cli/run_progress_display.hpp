#pragma once
// `drapelab run`'s progress on a terminal: the experiment's progress block (ProgressReporter)
// for one run, redrawn on stderr at every 1 % of the simulated time, so that a long run shows
// how far it is and how long it has left. An observer: it reads the simulation's time and
// never changes a step (docs/outputs.md).
#include <string>

#include "experiments/run/simulation.hpp"
#include "experiments/sweep/progress_reporter.hpp"

namespace drape {

/// Shows one run's progress; finish() leaves the block on the screen with the run's status.
class RunProgressDisplay : public SimulationObserver {
 public:
  /// `id` names the run in the block (the scene file); writes to `out`.
  RunProgressDisplay(std::string id, std::ostream& out);
  void on_start(const Simulation& simulation) override;
  void on_step(const Simulation& simulation, bool event) override;
  /// The run ended with `status` (ok, diverged, failed).
  void finish(const std::string& status);

 private:
  std::string m_id;
  ProgressReporter m_reporter;
  double m_shown = -1.0;  // the fraction last drawn
};

}  // namespace drape
