#pragma once
// frames/frames.vtk.series: ParaView's file-series meta file, a JSON list of the legacy VTK
// frames with the simulated time of each. ParaView's PVD reader (.pvd) takes XML VTK files
// only, while its file-series readers accept a `.series` file beside any reader's files, so
// the frames stay legacy .vtk and this file gives their times (docs/outputs.md, frames/).
#include <filesystem>
#include <fstream>
#include <string>

namespace drape {

/// Lists frame files with their times. Each frame appends its entry in place of the closing
/// brackets and writes them again behind it, in one write: the file is complete JSON after every
/// frame, so a run that diverges or is killed still leaves a series ParaView can open, and a
/// frame costs the same however many came before it (rewriting the whole list made a run
/// quadratic in its frames).
class VtkSeries {
 public:
  /// Writes `file` once the first frame is added.
  explicit VtkSeries(std::filesystem::path file) : m_file(std::move(file)) {}
  /// Appends a frame (its file name relative to the series file) at simulated time t [s];
  /// a failed write throws OutputError (run_files.hpp).
  void add(const std::string& name, double t);

 private:
  std::filesystem::path m_file;
  std::ofstream m_out;
  std::streamoff m_tail = 0;  ///< where the closing brackets start
};

}  // namespace drape
