#include "experiments/output/series_writers.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "experiments/output/run_files.hpp"

namespace drape {

OutputClock::OutputClock(double interval, double duration)
    : m_interval(interval), m_tolerance(1e-12 * std::max(1.0, duration)), m_next(interval) {}

bool OutputClock::due(const Simulation& simulation) {
  const double t = simulation.time();
  if (m_interval > 0.0 && t < m_next - m_tolerance && !simulation.at_end()) return false;
  while (m_interval > 0.0 && m_next <= t + m_tolerance)
    m_next = static_cast<double>(++m_ticks + 1) * m_interval;
  return true;
}

bool OutputClock::due_at_stop(const Simulation& simulation) const {
  return !simulation.status().ended() && simulation.time() > m_written;
}

EnergyWriter::EnergyWriter(const std::filesystem::path& file, double interval, double duration)
    : m_file(file), m_out(open_for_writing(file)), m_clock(interval, duration) {
  m_out << "t,kinetic,spring,gravity,collision,total\n";
}

void EnergyWriter::on_start(const Simulation& simulation) {
  m_initial = energy_of(simulation.system(), simulation.state());
  write(simulation);
}

void EnergyWriter::on_step(const Simulation& simulation, bool /*event*/) {
  if (m_clock.due(simulation)) write(simulation);
}

void EnergyWriter::write(const Simulation& simulation) {
  m_last = energy_of(simulation.system(), simulation.state());
  m_drift_max_abs = std::max(m_drift_max_abs, std::abs(m_last.total() - m_initial.total()));
  m_rise_max_abs = std::max(m_rise_max_abs, m_last.total() - m_initial.total());
  const EnergyBreakdown& e = m_last;
  m_out << fmt::format("{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n", simulation.time(),
                       e.kinetic, e.spring, e.gravity, e.collision, e.total());
  check_written(m_out, m_file);
  m_clock.wrote(simulation.time());
}

void EnergyWriter::on_end(const Simulation& simulation) {
  if (m_clock.due_at_stop(simulation)) write(simulation);
  finish_written(m_out, m_file);
}

HandsWriter::HandsWriter(const std::filesystem::path& file, double interval, double duration)
    : m_file(file), m_out(open_for_writing(file)), m_clock(interval, duration) {
  m_out << "t,hand,available,x,y,z,candidate,distance,held\n";
}

void HandsWriter::on_start(const Simulation& simulation) { write(simulation); }

void HandsWriter::on_step(const Simulation& simulation, bool /*event*/) {
  if (m_clock.due(simulation)) write(simulation);
}

void HandsWriter::write(const Simulation& simulation) {
  const double t = simulation.time();
  for (const HandStatus& h : simulation.manipulator().hands(t, simulation.state()))
    m_out << fmt::format("{:.17g},{},{},{:.17g},{:.17g},{:.17g},{},{:.17g},{}\n", t,
                         hand_name(h.hand), h.available ? 1 : 0, h.position.x(),
                         h.position.y(), h.position.z(), h.candidate, h.distance, h.held);
  check_written(m_out, m_file);
  m_clock.wrote(t);
}

void HandsWriter::on_end(const Simulation& simulation) {
  if (m_clock.due_at_stop(simulation)) write(simulation);
  finish_written(m_out, m_file);
}

}  // namespace drape
