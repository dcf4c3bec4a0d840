#pragma once
// One run folder as the viewer shows it: the cloth's frames (trace.csv, else the final
// state.csv), the dress form (dummy.csv), the hands (hands.csv), the energy (energy.csv) and
// the summary (docs/outputs.md, docs/viewer.md).
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace drape {

/// The cloth particles at one time.
struct ViewerFrame {
  double t = 0.0;
  std::vector<float> positions;  ///< xyz per particle, particle index order
  std::vector<int> fixed;        ///< indices of fixed particles (pinned, held, attached, mapped)
  bool event = false;            ///< written right after a manipulation event
};

/// One hand's rows of hands.csv.
struct ViewerHand {
  std::string name;  ///< `left` or `right`
  std::vector<double> t;
  std::vector<float> positions;  ///< xyz per row
  std::vector<int> available, candidate, held;
};

/// Everything the page needs from one run folder.
struct ViewerRun {
  std::string name;    ///< the folder's name
  std::string source;  ///< `trace.csv` or `state.csv`
  int rows = 0, cols = 0;
  nlohmann::json summary;  ///< summary.json as written
  std::vector<ViewerFrame> frames;
  int dummy_sections = 0, dummy_points = 0;
  std::vector<float> dummy_positions;  ///< xyz per object particle
  std::vector<ViewerHand> hands;
  std::vector<double> energy_t, energy_kinetic, energy_total;
};

/// Reads a run folder. Throws InputError naming the folder or the file when it is not a run
/// (no summary.json) or a file is malformed (missing column, bad number, wrong particle count).
ViewerRun read_viewer_run(const std::filesystem::path& dir);

}  // namespace drape
