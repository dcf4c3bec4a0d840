#pragma once
// The optional time series of a run besides energy.csv: trace.csv (every particle's position,
// velocity and contact) and VTK frames, at each multiple of their interval and right after every
// event. A frame time that a step end reaches within round-off is written from that step end;
// one inside a step from the simulation's interpolant (Simulation::interpolate), so the frame
// rate does not depend on the step and recording never changes a step (docs/outputs.md).
#include <Eigen/Core>
#include <filesystem>
#include <fstream>
#include <optional>

#include "core/model/cloth_system.hpp"
#include "core/scene/scene.hpp"
#include "experiments/run/simulation.hpp"
#include "experiments/output/vtk_series.hpp"

namespace drape {

/// The object particle within the collision threshold of particle i at state y, -1 for none: its
/// switches between frames are the collision switching the vibration metrics count.
int contact_index(const ClothSystem& system, const Eigen::VectorXd& y, int i);

/// Writes trace.csv, frames/frame_NNNNN.vtk and frames/frames.vtk.series for the intervals of a scene's `output`.
class FrameRecorder : public SimulationObserver {
 public:
  /// Opens the files the output options ask for (none when both intervals are 0).
  FrameRecorder(const OutputOptions& options, const std::filesystem::path& out_dir,
                const ClothSystem& system);
  void on_start(const Simulation& simulation) override;
  void on_step(const Simulation& simulation, bool event) override;
  /// Flushes trace.csv; a failed write throws OutputError (run_files.hpp).
  void on_end(const Simulation& simulation) override;
  bool interpolates() const override { return m_trace.has_value() || m_vtk_interval > 0.0; }

 private:
  /// Writes the frames of one series (trace or VTK) that fall in the last step.
  template <class Write>
  void record(const Simulation& simulation, bool event, double interval, double& next,
              Write write);
  void write_trace(double t, const Eigen::VectorXd& y, bool event);
  void write_vtk(const Simulation& simulation, double t, const Eigen::VectorXd& y);

  const ClothSystem& m_system;
  double m_trace_interval;
  double m_vtk_interval;
  double m_next_trace = 0.0;
  double m_next_vtk = 0.0;
  int m_vtk_count = 0;
  std::filesystem::path m_frames_dir;
  std::optional<std::ofstream> m_trace;
  VtkSeries m_series;
  std::filesystem::path m_trace_file;
};

}  // namespace drape
