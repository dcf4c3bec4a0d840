#include "experiments/output/frame_recorder.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "core/dummy/dummy.hpp"
#include "experiments/output/run_files.hpp"
#include "experiments/output/vtk_writer.hpp"

namespace drape {

namespace {

// A frame time this close after a step end counts as reached by it (round-off of t += dt).
double reach_tolerance(double interval) { return 1e-9 * interval; }

}  // namespace

FrameRecorder::FrameRecorder(const OutputOptions& options, const std::filesystem::path& out_dir,
                             const ClothSystem& system)
    : m_system(system),
      m_trace_interval(options.trace_interval),
      m_vtk_interval(options.vtk_interval),
      m_frames_dir(out_dir / "frames"),
      m_series(out_dir / "frames" / "frames.vtk.series"),
      m_trace_file(out_dir / "trace.csv") {
  if (m_trace_interval > 0.0) {
    m_trace.emplace(open_for_writing(m_trace_file));
    *m_trace << "t,index,x,y,z,vx,vy,vz,fixed,contact,event\n";
  }
  if (m_vtk_interval > 0.0) {
    std::filesystem::create_directories(m_frames_dir);
    if (system.dummy()) write_dummy_vtk(m_frames_dir / "dummy.vtk", *system.dummy());
  }
}

void FrameRecorder::on_start(const Simulation& simulation) {
  on_step(simulation, true);
}

void FrameRecorder::on_step(const Simulation& simulation, bool event) {
  if (m_trace)
    record(simulation, event, m_trace_interval, m_next_trace,
           [this](double t, const Eigen::VectorXd& y, bool e) { write_trace(t, y, e); });
  if (m_vtk_interval > 0.0)
    record(simulation, event, m_vtk_interval, m_next_vtk,
           [this, &simulation](double t, const Eigen::VectorXd& y, bool) {
             write_vtk(simulation, t, y);
           });
}

template <class Write>
void FrameRecorder::record(const Simulation& simulation, bool event, double interval,
                           double& next, Write write) {
  const double t = simulation.time();
  const double tolerance = reach_tolerance(interval);
  // Frame times strictly inside the step: sampled from the interpolant.
  for (; next < t - tolerance; next += interval)
    write(next, simulation.interpolate(next), false);
  // A frame time the step end reaches, or an event: the step end itself.
  const bool reached = t >= next - tolerance;
  if (reached || event) write(t, simulation.state(), event);
  for (; t >= next - tolerance; next += interval) {}
}

int contact_index(const ClothSystem& system, const Eigen::VectorXd& y, int i) {
  const Dummy* dummy = system.dummy();
  if (!dummy) return -1;
  return dummy->nearest_within(y.segment<3>(3 * i), system.params().collision.threshold).index;
}

void FrameRecorder::write_vtk(const Simulation& simulation, double t, const Eigen::VectorXd& y) {
  const auto n = static_cast<std::size_t>(m_system.num_particles());
  ClothFrameData data{std::vector<int>(n, 0), std::vector<int>(n, -1)};
  // Holds change only at events, which are step ends: the holds after the last step are the
  // holds at every frame time inside it.
  for (const HandStatus& hand : simulation.manipulator().hands(t, y))
    if (hand.held >= 0) data.held[static_cast<std::size_t>(hand.held)] = 1;
  for (std::size_t i = 0; i < n; ++i) data.contact[i] = contact_index(m_system, y, static_cast<int>(i));
  const std::string name = fmt::format("frame_{:05d}.vtk", m_vtk_count++);
  write_cloth_vtk(m_frames_dir / name, m_system, y, t, data);
  m_series.add(name, t);
}

void FrameRecorder::write_trace(double t, const Eigen::VectorXd& y, bool event) {
  const int n = m_system.num_particles();
  const Eigen::Index n3 = 3 * static_cast<Eigen::Index>(n);
  for (int i = 0; i < n; ++i) {
    const Vec3 x = y.segment<3>(3 * i);
    const Vec3 v = y.segment<3>(n3 + 3 * i);
    *m_trace << fmt::format("{:.17g},{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{},{},{}\n",
                            t, i, x.x(), x.y(), x.z(), v.x(), v.y(), v.z(),
                            m_system.constraints().is_fixed(i) ? 1 : 0, contact_index(m_system, y, i), event ? 1 : 0);
  }
  check_written(*m_trace, m_trace_file);
}

void FrameRecorder::on_end(const Simulation& /*simulation*/) {
  if (m_trace) finish_written(*m_trace, m_trace_file);
}

}  // namespace drape
