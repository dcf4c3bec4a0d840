#pragma once
// Small run folders written by hand for the viewer's tests.
#include <filesystem>
#include <fstream>
#include <string>

namespace drape::testing {

/// A fresh empty folder under the system's temporary folder.
inline std::filesystem::path fresh_folder(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("drape_viewer_test_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

inline void write_text(const std::filesystem::path& file, const std::string& text) {
  std::ofstream(file) << text;
}

/// A 1 x 2 cloth run with two trace frames, particle 0 pinned, one hold event, energy rows to
/// its end.
inline std::filesystem::path tiny_run(const std::string& name) {
  const auto dir = fresh_folder(name);
  write_text(dir / "summary.json",
             R"({"status": "ok", "integrator": "leapfrog", "dt": 0.001, "duration": 0.1,
                 "sim_time": 0.1, "events": [{"t": 0.05, "type": "hold", "row": 0, "col": 1}],
                 "scene": {"cloth": {"rows": 1, "cols": 2}, "pins": [[0, 0]]}})");
  write_text(dir / "trace.csv",
             "t,index,x,y,z,vx,vy,vz,fixed,contact,event\n"
             "0,0,0,1,0,0,0,0,1,-1,0\n0,1,0.02,1,0,0,0,0,0,-1,0\n"
             "0.05,0,0,1,0,0,0,0,1,-1,1\n0.05,1,0.02,0.99,0.01,0,0,0,1,-1,1\n");
  write_text(dir / "energy.csv",
             "t,kinetic,spring,gravity,collision,total\n0,0,0,1,0,1\n0.05,0.5,0,0.9,0,1.4\n"
             "0.1,0.25,0,0.95,0,1.2\n");
  return dir;
}

}  // namespace drape::testing
