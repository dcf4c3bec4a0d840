#include "experiments/output/event_trace_recorder.hpp"

#include "experiments/output/frame_recorder.hpp"

namespace drape {

EventTraceRecorder::Files::Files(const std::filesystem::path& dir, std::size_t n)
    : t(dir / "t.npy", "<f8", 8, {}),
      x(dir / "x.npy", "<f4", 4, {n, 3}),
      v(dir / "v.npy", "<f4", 4, {n, 3}),
      fixed(dir / "fixed.npy", "|u1", 1, {n}),
      contact(dir / "contact.npy", "<i4", 4, {n}) {}

EventTraceRecorder::EventTraceRecorder(const OutputOptions& options,
                                       const std::filesystem::path& out_dir,
                                       const ClothSystem& system)
    : m_system(system),
      m_interval(options.event_trace_interval),
      m_window(options.event_trace_window) {
  if (m_interval <= 0.0) return;
  const auto dir = out_dir / "event_trace";
  std::filesystem::create_directories(dir);
  const auto n = static_cast<std::size_t>(system.num_particles());
  m_files.emplace(dir, n);
  m_buffer.resize(3 * n);
  m_fixed.resize(n);
  m_contact.resize(n);
}

void EventTraceRecorder::on_start(const Simulation& simulation) { on_step(simulation, true); }

void EventTraceRecorder::on_step(const Simulation& simulation, bool event) {
  if (!m_files) return;
  const double t = simulation.time();
  // A frame time this close before a step end counts as reached by it (round-off of t += dt).
  const double tolerance = 1e-9 * m_interval;
  const auto next = [this] { return m_window_start + static_cast<double>(m_frame) * m_interval; };
  // Frames strictly inside the step and inside the current window: from the interpolant.
  for (; next() < t - tolerance && next() <= m_window_end + tolerance; ++m_frame)
    write(next(), simulation.interpolate(next()));
  if (event) {
    // A new window starts at the event, from the state the event left.
    m_window_start = t;
    m_window_end = t + m_window;
    m_frame = 0;
  }
  if (t >= next() - tolerance && next() <= m_window_end + tolerance) {
    write(t, simulation.state());
    ++m_frame;
  }
}

void EventTraceRecorder::on_end(const Simulation& /*simulation*/) {
  if (!m_files) return;
  m_files->t.close();
  m_files->x.close();
  m_files->v.close();
  m_files->fixed.close();
  m_files->contact.close();
}

void EventTraceRecorder::write(double t, const Eigen::VectorXd& y) {
  const int n = m_system.num_particles();
  const Eigen::Index n3 = 3 * static_cast<Eigen::Index>(n);
  m_files->t.append(&t);
  // Single precision: 0.1 micrometre at a metre, far below the millimetre vibrations measured.
  Eigen::Map<Eigen::VectorXf>(m_buffer.data(), n3) = y.head(n3).cast<float>();
  m_files->x.append(m_buffer.data());
  Eigen::Map<Eigen::VectorXf>(m_buffer.data(), n3) = y.segment(n3, n3).cast<float>();
  m_files->v.append(m_buffer.data());
  for (int i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    m_fixed[k] = m_system.constraints().is_fixed(i) ? 1 : 0;
    m_contact[k] = contact_index(m_system, y, i);
  }
  m_files->fixed.append(m_fixed.data());
  m_files->contact.append(m_contact.data());
}

}  // namespace drape
