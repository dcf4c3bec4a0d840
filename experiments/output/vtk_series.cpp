#include "experiments/output/vtk_series.hpp"

#include <nlohmann/json.hpp>

#include "experiments/output/run_files.hpp"

namespace drape {

void VtkSeries::add(const std::string& name, double t) {
  const bool first = !m_out.is_open();
  if (first) {
    m_out = open_for_writing(m_file);
    m_out << R"({"file-series-version": "1.0", "files": [)";
  } else {
    m_out.seekp(m_tail);
  }
  m_out << (first ? "\n" : ",\n") << nlohmann::json{{"name", name}, {"time", t}}.dump();
  m_tail = m_out.tellp();
  // Buffered until the flush, so the entry and the brackets reach the file in one write.
  m_out << "\n]}\n";
  finish_written(m_out, m_file);
}

}  // namespace drape
