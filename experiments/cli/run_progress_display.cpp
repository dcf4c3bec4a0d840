#include "experiments/cli/run_progress_display.hpp"

namespace drape {

RunProgressDisplay::RunProgressDisplay(std::string id, std::ostream& out)
    : m_id(std::move(id)), m_reporter(1, ProgressStyle::Terminal, out) {
  m_reporter.run_started(m_id);
}

void RunProgressDisplay::on_start(const Simulation& simulation) { on_step(simulation, false); }

void RunProgressDisplay::on_step(const Simulation& simulation, bool /*event*/) {
  const double duration = simulation.settings().duration;
  const double fraction = duration > 0.0 ? simulation.time() / duration : 1.0;
  // As progress.json (RunProgressFile): at most 100 redraws a run, whatever its step count.
  if (fraction - m_shown < 0.01) return;
  m_shown = fraction;
  m_reporter.run_progress(m_id, fraction);
  m_reporter.redraw();
}

void RunProgressDisplay::finish(const std::string& status) {
  m_reporter.run_finished(m_id, status, false);
  m_reporter.finish();
}

}  // namespace drape
