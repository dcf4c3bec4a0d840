#pragma once
// The time series a run writes at its output times (docs/outputs.md): energy.csv and hands.csv.
// Rows are written at step ends, at the first step end at or after each multiple of
// output.energy_interval, with the step's exact time; they never change a step.
#include <filesystem>
#include <fstream>

#include "experiments/run/simulation.hpp"

namespace drape {

/// Multiples of an interval, each passed once: due(t) is true at the first time at or after the
/// next multiple not yet passed, always with interval 0, and at the end of the run.
class OutputClock {
 public:
  OutputClock(double interval, double duration);
  bool due(const Simulation& simulation);
  /// Records that a row was written at time t.
  void wrote(double t) { m_written = t; }
  /// At on_end: true when the run was stopped before its end (a live run's Ctrl-C) at a time
  /// with no row yet, the row its replay, which ends there, writes.
  bool due_at_stop(const Simulation& simulation) const;

 private:
  double m_written = -1.0;
  double m_interval;
  double m_tolerance;
  long m_ticks = 0;  // output times are multiples of the interval, not running sums
  double m_next;
};

/// energy.csv: `t,kinetic,spring,gravity,collision,total` at t = 0 and at the output times,
/// and the drift of the total over those rows. A failed write throws OutputError (run_files.hpp).
class EnergyWriter : public SimulationObserver {
 public:
  EnergyWriter(const std::filesystem::path& file, double interval, double duration);
  void on_start(const Simulation& simulation) override;
  void on_step(const Simulation& simulation, bool event) override;
  void on_end(const Simulation& simulation) override;

  const EnergyBreakdown& initial() const { return m_initial; }
  /// The energy of the last row written.
  const EnergyBreakdown& last() const { return m_last; }
  /// max |E(t) - E(0)| over the rows written [J].
  double drift_max_abs() const { return m_drift_max_abs; }
  /// max (E(t) - E(0), 0) over the rows written [J]: what the run gained. Without driven
  /// particles a cloth's energy can only fall (damping, contact); a step beyond the stability
  /// limit makes it grow, also where the growth saturates below the runaway bound.
  double rise_max_abs() const { return m_rise_max_abs; }

 private:
  void write(const Simulation& simulation);

  std::filesystem::path m_file;
  std::ofstream m_out;
  OutputClock m_clock;
  EnergyBreakdown m_initial, m_last;
  double m_drift_max_abs = 0.0, m_rise_max_abs = 0.0;
};

/// hands.csv: `t,hand,available,x,y,z,candidate,distance,held` at the output times.
class HandsWriter : public SimulationObserver {
 public:
  HandsWriter(const std::filesystem::path& file, double interval, double duration);
  void on_start(const Simulation& simulation) override;
  void on_step(const Simulation& simulation, bool event) override;
  void on_end(const Simulation& simulation) override;

 private:
  void write(const Simulation& simulation);

  std::filesystem::path m_file;
  std::ofstream m_out;
  OutputClock m_clock;
};

}  // namespace drape
