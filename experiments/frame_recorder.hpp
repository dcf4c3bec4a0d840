#pragma once
// The optional time series of a run besides energy.csv: trace.csv (every particle's position,
// velocity and contact) and VTK frames, written at the first step at or after each multiple of
// their interval and right after every event, so recording never changes the step sequence.
#include <Eigen/Core>
#include <filesystem>
#include <fstream>
#include <optional>

#include "core/cloth_system.hpp"
#include "core/scene.hpp"

namespace drape {

/// Writes trace.csv and frames/frame_NNNNN.vtk for the intervals of a scene's `output`.
class FrameRecorder {
 public:
  /// Opens the files the output options ask for (none when both intervals are 0).
  FrameRecorder(const OutputOptions& options, const std::filesystem::path& out_dir,
                const ClothSystem& system);
  /// Records the state reached at t when an interval has passed, or always when `event`.
  void record(double t, const Eigen::VectorXd& y, bool event);

 private:
  void write_trace(double t, const Eigen::VectorXd& y, bool event);

  const ClothSystem& m_system;
  double m_trace_interval;
  double m_vtk_interval;
  double m_next_trace = 0.0;
  double m_next_vtk = 0.0;
  int m_vtk_count = 0;
  std::filesystem::path m_frames_dir;
  std::optional<std::ofstream> m_trace;
};

}  // namespace drape
