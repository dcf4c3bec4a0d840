#include "experiments/sweep/run_progress_file.hpp"

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>

#include "experiments/output/run_files.hpp"
#include "experiments/sweep/experiment_folder.hpp"

namespace drape {

std::filesystem::path progress_file(const std::filesystem::path& run_dir) {
  return run_dir / experiment_run_file::progress;
}

std::optional<double> read_run_progress(const std::filesystem::path& run_dir) {
  std::ifstream in(progress_file(run_dir));
  if (!in) return std::nullopt;
  // write_json renames a complete file into place: a parse error means a foreign file.
  const nlohmann::json doc = nlohmann::json::parse(in, nullptr, false);
  if (!doc.is_object() || !doc.contains("fraction") || !doc["fraction"].is_number())
    return std::nullopt;
  return std::clamp(doc["fraction"].get<double>(), 0.0, 1.0);
}

void RunProgressFile::set_part(int part, int parts) {
  m_parts = std::max(1, parts);
  m_part = std::clamp(part, 0, m_parts - 1);
}

double RunProgressFile::run_fraction(double simulation_fraction) const {
  return (m_part + std::clamp(simulation_fraction, 0.0, 1.0)) / m_parts;
}

void RunProgressFile::report(const Simulation& simulation) {
  const double duration = simulation.settings().duration;
  const double fraction = run_fraction(duration > 0.0 ? simulation.time() / duration : 1.0);
  // A file per 1 % keeps the cost at 100 small writes a run, whatever its step count.
  if (fraction - m_written < 0.01 && !(fraction >= 1.0 && m_written < 1.0)) return;
  m_written = fraction;
  write_json(progress_file(m_dir), {{"fraction", fraction}, {"time", simulation.time()},
                                    {"duration", duration}});
}

}  // namespace drape
