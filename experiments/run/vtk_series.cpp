#include "experiments/run/vtk_series.hpp"

#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "experiments/run/run_files.hpp"

namespace drape {

void VtkSeries::add(const std::string& name, double t) {
  m_entries.push_back({name, t});
  nlohmann::json files = nlohmann::json::array();
  for (const Entry& e : m_entries) files.push_back({{"name", e.name}, {"time", e.time}});
  // Write beside and rename, so that a reader never sees half a file.
  const std::filesystem::path partial = m_file.string() + ".partial";
  {
    std::ofstream out = open_for_writing(partial);
    out << nlohmann::json{{"file-series-version", "1.0"}, {"files", files}}.dump(1) << "\n";
    finish_written(out, partial);
  }
  std::filesystem::rename(partial, m_file);
}

}  // namespace drape
