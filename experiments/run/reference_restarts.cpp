#include "experiments/run/reference_restarts.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "core/scene/input_error.hpp"
#include "experiments/run/run_files.hpp"

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

/// One horizon of one branch: the method's positions at its end, then the errors once the
/// reference has got there.
struct BranchRow {
  double t = 0.0;
  std::string events;  ///< "start", or the reference's event types at t joined by '+'
  double horizon = 0.0;
  std::string status = "ok";
  std::string reason;
  Eigen::VectorXd start_x;   ///< the reference's (and so the method's) positions at t
  Eigen::VectorXd method_x;  ///< the method's positions at t + horizon (when ok)
  bool resolved = false;
  double error_rms = nan, error_max = nan, reference_motion_rms = nan;
};

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

/// Watches the reference: branches the method at its start and after each event, and measures
/// each branch once the reference reaches the branch's horizon.
class Brancher final : public SimulationObserver {
 public:
  Brancher(Simulation& method, const std::vector<double>& horizons, double duration)
      : m_method(method), m_horizons(horizons), m_duration(duration) {}

  void on_start(const Simulation& reference) override { branch(reference, "start"); }
  void on_step(const Simulation& reference, bool event) override {
    resolve(reference);
    if (event) branch(reference, event_types(reference));
  }
  bool interpolates() const override { return true; }

  std::vector<BranchRow>& rows() { return m_rows; }

 private:
  double tolerance() const { return 1e-12 * std::max(1.0, m_duration); }

  static std::string event_types(const Simulation& reference) {
    std::string types;
    for (const ManipulationEvent& e : reference.manipulator().events()) {
      if (std::abs(e.t - reference.time()) > 1e-12 || e.type == "ignored") continue;
      if (("+" + types + "+").find("+" + e.type + "+") != std::string::npos) continue;
      types += (types.empty() ? "" : "+") + e.type;
    }
    return types.empty() ? "event" : types;
  }

  void branch(const Simulation& reference, const std::string& events) {
    const Eigen::Index n3 = reference.state().size() / 2;
    const double t = reference.time();
    m_method.branch_from(reference);
    std::string status = "ok", reason;
    for (const double horizon : m_horizons) {
      const double end = t + horizon;
      if (end > m_duration + tolerance()) break;  // past the run: nothing to compare with
      BranchRow row;
      row.t = t;
      row.events = events;
      row.horizon = horizon;
      row.start_x = reference.state().head(n3);
      if (status == "ok") {
        m_method.advance(end);
        const RunStatus& s = m_method.status();
        if (s.status != "running" && s.status != "ok") status = s.status, reason = s.reason;
      }
      row.status = status;
      row.reason = reason;
      if (status == "ok") row.method_x = m_method.interpolate(end).head(n3);
      m_rows.push_back(std::move(row));
    }
  }

  void resolve(const Simulation& reference) {
    const Eigen::Index n3 = reference.state().size() / 2;
    for (BranchRow& row : m_rows) {
      const double end = row.t + row.horizon;
      if (row.resolved || end > reference.time() + tolerance()) continue;
      row.resolved = true;
      const Eigen::VectorXd x = reference.interpolate(end).head(n3);
      row.reference_motion_rms = particle_distance(x, row.start_x).first;
      if (row.status == "ok")
        std::tie(row.error_rms, row.error_max) = particle_distance(row.method_x, x);
      row.method_x.resize(0);  // measured: the memory goes back
      row.start_x.resize(0);
    }
  }

  Simulation& m_method;
  std::vector<double> m_horizons;
  double m_duration;
  std::vector<BranchRow> m_rows;
};

}  // namespace

ReferenceRestarts::ReferenceRestarts(const Scene& scene)
    : m_options(scene.restart_error),
      m_reference(reference_scene(scene), "restart_error.reference"),
      m_method(scene) {
  m_method.simulation().keep_step_ends();
}

nlohmann::json ReferenceRestarts::run(const std::filesystem::path& csv) {
  const auto wall_start = std::chrono::steady_clock::now();
  Simulation& reference = m_reference.simulation();
  Brancher brancher(m_method.simulation(), m_options.horizons, m_reference.scene().duration);
  reference.add_observer(brancher);
  const RunStatus& status = reference.run();

  int measured = 0, failed = 0;
  nlohmann::json failures = nlohmann::json::array();
  write_file_atomic(csv, ".tmp", [&](std::ostream& out) {
    out << "t,events,horizon,status,error_rms,error_max,reference_motion_rms\n";
    for (const BranchRow& row : brancher.rows()) {
      const std::string row_status = row.resolved ? row.status : "reference_" + status.status;
      out << fmt::format("{},{},{},{},{},{},{}\n", row.t, row.events, row.horizon, row_status,
                         row.error_rms, row.error_max, row.reference_motion_rms);
      if (row_status == "ok") {
        ++measured;
      } else {
        ++failed;
        if (failures.size() < 20)
          failures.push_back({{"t", row.t}, {"horizon", row.horizon}, {"status", row_status},
                              {"reason", row.reason}});
      }
    }
  });
  return {{"file", csv.filename().string()},
          {"horizons", m_options.horizons},
          {"reference", m_options.reference},
          {"reference_status", status.status},
          {"reference_reason", status.reason},
          {"rows", measured + failed},
          {"rows_failed", failed},
          {"failures", failures},
          {"wall_seconds",
           std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count()}};
}

}  // namespace drape
