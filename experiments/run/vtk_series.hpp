#pragma once
// frames/frames.vtk.series: ParaView's file-series meta file, a JSON list of the legacy VTK
// frames with the simulated time of each. ParaView's PVD reader (.pvd) takes XML VTK files
// only, while its file-series readers accept a `.series` file beside any reader's files, so
// the frames stay legacy .vtk and this file gives their times (docs/outputs.md, frames/).
#include <filesystem>
#include <string>
#include <vector>

namespace drape {

/// Lists frame files with their times; the file is rewritten after every frame, so a run that
/// diverges or is interrupted still leaves a series ParaView can open.
class VtkSeries {
 public:
  /// Writes `file` once the first frame is added.
  explicit VtkSeries(std::filesystem::path file) : m_file(std::move(file)) {}
  /// Appends a frame (its file name relative to the series file) at simulated time t [s].
  void add(const std::string& name, double t);

 private:
  struct Entry {
    std::string name;
    double time;
  };
  std::filesystem::path m_file;
  std::vector<Entry> m_entries;
};

}  // namespace drape
