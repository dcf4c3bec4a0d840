#pragma once
// event_trace/: every particle's position, velocity, fixed flag and contact at a fine fixed rate
// (output.event_trace_interval, e.g. 1 ms) for output.event_trace_window seconds after each
// event and after the start, so that the vibration after an event is sampled well above its
// frequencies whatever the step (docs/outputs.md, "event_trace/"). Frames inside a step come
// from the simulation's interpolant, as trace.csv's do: recording never changes a step. Binary
// NumPy files, because a CSV row per particle at 1 kHz would be about 70 MB a second of a 20 x 20
// cloth.
#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <vector>

#include "core/model/cloth_system.hpp"
#include "core/scene/scene.hpp"
#include "experiments/output/npy_writer.hpp"
#include "experiments/run/simulation.hpp"

namespace drape {

class EventTraceRecorder : public SimulationObserver {
 public:
  /// Writes nothing when options.event_trace_interval is 0.
  EventTraceRecorder(const OutputOptions& options, const std::filesystem::path& out_dir,
                     const ClothSystem& system);
  void on_start(const Simulation& simulation) override;
  void on_step(const Simulation& simulation, bool event) override;
  void on_end(const Simulation& simulation) override;
  bool interpolates() const override { return m_interval > 0.0; }

 private:
  void write(double t, const Eigen::VectorXd& y);

  /// event_trace/{t,x,v,fixed,contact}.npy for n particles.
  struct Files {
    Files(const std::filesystem::path& dir, std::size_t n);
    NpyWriter t, x, v, fixed, contact;
  };
  const ClothSystem& m_system;
  double m_interval;
  double m_window;
  double m_window_start = 0.0;  ///< the event that opened the current window
  double m_window_end = -1.0;   ///< frames are written up to this time
  long m_frame = 0;             ///< the next frame is m_window_start + m_frame x m_interval
  std::optional<Files> m_files;
  std::vector<float> m_buffer;
  std::vector<std::uint8_t> m_fixed;
  std::vector<std::int32_t> m_contact;
};

}  // namespace drape
