#include "experiments/output/reference_restarts.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "experiments/output/run_files.hpp"

namespace drape {

namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

Scene reference_scene(const Scene& scene) {
  Scene reference = scene;
  reference.integrator = scene.restart_error.reference;
  reference.source["integrator"] = scene.restart_error.reference;
  reference.source.erase("restart_error");
  reference.restart_error = {};
  return reference;
}

/// RMS over particles of |a_i - b_i|, and the largest |a_i - b_i|.
std::pair<double, double> particle_distance(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  const Eigen::Index n = a.size() / 3;
  double sum = 0.0, largest = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double d2 = (a.segment<3>(3 * i) - b.segment<3>(3 * i)).squaredNorm();
    sum += d2;
    largest = std::max(largest, d2);
  }
  return {std::sqrt(sum / static_cast<double>(std::max<Eigen::Index>(n, 1))), std::sqrt(largest)};
}

/// One horizon of one branch: the reference's positions at its end, then the errors once the
/// run has got there.
struct BranchRow {
  double t = 0.0;
  std::string events;  ///< "start", or the run's event types at t joined by '+'
  double horizon = 0.0;
  std::string status = "ok";  ///< ok, or reference_<status> when the reference's branch ended
  std::string reason;         ///< why the reference's branch ended
  Eigen::VectorXd reference_x;  ///< the reference's positions at t + horizon (when ok)
  bool resolved = false;
  double error_rms = nan, error_max = nan, reference_motion_rms = nan;
};

}  // namespace

/// Watches the run: branches the reference at its start and after each event, and measures
/// each branch once the run reaches the branch's horizon.
class RestartBrancher final : public SimulationObserver {
 public:
  RestartBrancher(Simulation& reference, const std::vector<double>& horizons, double duration)
      : m_reference(reference), m_horizons(horizons), m_duration(duration) {}

  void on_start(const Simulation& run) override { branch(run, "start"); }
  void on_step(const Simulation& run, bool event) override {
    resolve(run);
    if (event) branch(run, event_types(run));
  }
  bool interpolates() const override { return true; }

  const std::vector<BranchRow>& rows() const { return m_rows; }
  double wall_seconds() const { return m_wall_seconds; }

 private:
  double tolerance() const { return 1e-12 * std::max(1.0, m_duration); }

  static std::string event_types(const Simulation& run) {
    std::string types;
    for (const ManipulationEvent& e : run.manipulator().events()) {
      if (std::abs(e.t - run.time()) > 1e-12 || e.type == "ignored") continue;
      if (("+" + types + "+").find("+" + e.type + "+") != std::string::npos) continue;
      types += (types.empty() ? "" : "+") + e.type;
    }
    return types.empty() ? "event" : types;
  }

  void branch(const Simulation& run, const std::string& events) {
    const auto wall_start = std::chrono::steady_clock::now();
    const Eigen::Index n3 = run.state().size() / 2;
    const double t = run.time();
    const Eigen::VectorXd start_x = run.state().head(n3);
    m_reference.branch_from(run);
    std::string status = "ok", reason;
    for (const double horizon : m_horizons) {
      const double end = t + horizon;
      if (end > m_duration + tolerance()) break;  // past the run: nothing to compare with
      BranchRow row;
      row.t = t;
      row.events = events;
      row.horizon = horizon;
      if (status == "ok") {
        m_reference.advance(end);
        const RunStatus& s = m_reference.status();
        if (s.status != "running" && s.status != "ok") status = "reference_" + s.status, reason = s.reason;
      }
      row.status = status;
      row.reason = reason;
      if (status == "ok") {
        row.reference_x = m_reference.interpolate(end).head(n3);
        row.reference_motion_rms = particle_distance(row.reference_x, start_x).first;
      }
      m_rows.push_back(std::move(row));
    }
    m_wall_seconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  }

  void resolve(const Simulation& run) {
    const Eigen::Index n3 = run.state().size() / 2;
    for (BranchRow& row : m_rows) {
      const double end = row.t + row.horizon;
      if (row.resolved || end > run.time() + tolerance()) continue;
      row.resolved = true;
      if (row.status != "ok") continue;
      std::tie(row.error_rms, row.error_max) =
          particle_distance(run.interpolate(end).head(n3), row.reference_x);
      row.reference_x.resize(0);  // measured: the memory goes back
    }
  }

  Simulation& m_reference;
  std::vector<double> m_horizons;
  double m_duration;
  std::vector<BranchRow> m_rows;
  double m_wall_seconds = 0.0;
};

ReferenceRestarts::ReferenceRestarts(const Scene& scene)
    : m_options(scene.restart_error),
      m_reference(reference_scene(scene), "restart_error.reference") {
  m_reference.simulation().keep_step_ends();
  m_brancher = std::make_unique<RestartBrancher>(m_reference.simulation(), m_options.horizons,
                                                 scene.duration);
}

ReferenceRestarts::~ReferenceRestarts() = default;

SimulationObserver& ReferenceRestarts::observer() { return *m_brancher; }

nlohmann::json ReferenceRestarts::write(const std::filesystem::path& csv,
                                        const Simulation& run) const {
  int failed = 0;
  nlohmann::json failures = nlohmann::json::array();
  write_file_atomic(csv, ".tmp", [&](std::ostream& out) {
    out << "t,events,horizon,status,error_rms,error_max,reference_motion_rms\n";
    for (const BranchRow& row : m_brancher->rows()) {
      // A row the run never reached: the run ended (diverged or failed) before t + horizon.
      const std::string status = row.resolved ? row.status : run.status().status;
      out << fmt::format("{},{},{},{},{},{},{}\n", row.t, row.events, row.horizon, status,
                         row.error_rms, row.error_max, row.reference_motion_rms);
      if (status == "ok") continue;
      ++failed;
      if (failures.size() < 20)
        failures.push_back({{"t", row.t}, {"horizon", row.horizon}, {"status", status},
                            {"reason", row.resolved ? row.reason : run.status().reason}});
    }
  });
  return {{"file", csv.filename().string()},
          {"horizons", m_options.horizons},
          {"reference", m_options.reference},
          {"rows", m_brancher->rows().size()},
          {"rows_failed", failed},
          {"failures", failures},
          {"wall_seconds", m_brancher->wall_seconds()}};
}

}  // namespace drape
