#include "experiments/run_scene.hpp"

#include <chrono>
#include <cmath>
#include <fmt/format.h>

#include <optional>

#include "core/dummy_sources.hpp"
#include "core/input_config.hpp"
#include "core/manipulations.hpp"
#include "experiments/frame_recorder.hpp"
#include "experiments/run_files.hpp"
#include "integrators/registry.hpp"

namespace drape {

namespace {

/// Stops a run whose state no motion of this scene could reach.
///
/// Bound on any particle's speed: a free fall over the whole run, plus twice the fastest
/// prescribed motion, plus the speed one particle would have if it alone took all the kinetic
/// and elastic energy present at the start or right after an event (mapping, attach). A
/// physical motion stays below it; a numerical blow-up grows without bound and passes it within
/// a few steps.
class DivergenceCheck {
 public:
  explicit DivergenceCheck(const Scene& scene)
      : m_base(10.0 + 2.0 * scene.forces.gravity.norm() * scene.duration) {}

  /// Raises the bound by the energy stored in a state (call at the start and after events).
  void account_for(const ClothSystem& system, const EnergyBreakdown& e) {
    const double stored = std::max(0.0, e.kinetic + e.spring + e.collision);
    m_stored_speed = std::max(m_stored_speed, std::sqrt(2.0 * stored / system.particle_mass()));
  }

  /// An empty string when the state is sound, else the reason.
  std::string reason(const ClothSystem& system, double t, const Eigen::VectorXd& y) const {
    if (!y.allFinite()) return "non-finite state";
    const Eigen::Index n = system.num_particles();
    const auto v = y.tail(3 * n);
    double max_speed2 = 0.0;
    for (Eigen::Index i = 0; i < n; ++i)
      max_speed2 = std::max(max_speed2, v.segment<3>(3 * i).squaredNorm());
    const double limit = m_base + m_stored_speed + 2.0 * system.constraints().max_speed(t);
    if (max_speed2 > limit * limit)
      return fmt::format("runaway: a particle moves at {:.3g} m/s, above the bound {:.3g} m/s",
                         std::sqrt(max_speed2), limit);
    return {};
  }

 private:
  double m_base;
  double m_stored_speed = 0.0;
};

/// hands.csv: what each hand does at the output times (the candidate a viewer colours).
class HandsWriter {
 public:
  explicit HandsWriter(const std::filesystem::path& file) : m_out(file) {
    if (!m_out) throw std::runtime_error("cannot write " + file.string());
    m_out << "t,hand,available,x,y,z,candidate,distance,held\n";
  }
  void write(double t, const std::vector<HandStatus>& hands) {
    for (const HandStatus& h : hands)
      m_out << fmt::format("{:.17g},{},{},{:.17g},{:.17g},{:.17g},{},{:.17g},{}\n", t,
                           hand_name(h.hand), h.available ? 1 : 0, h.position.x(),
                           h.position.y(), h.position.z(), h.candidate, h.distance, h.held);
  }

 private:
  std::ofstream m_out;
};

EnergyBreakdown energy_of(const ClothSystem& system, const Eigen::VectorXd& y) {
  const Eigen::Index n3 = 3 * system.num_particles();
  return system.energy(ConstVecMap(y.data(), n3), ConstVecMap(y.data() + n3, n3));
}

nlohmann::json events_json(const Manipulator& manipulator, const Cloth& cloth) {
  nlohmann::json events = nlohmann::json::array();
  for (const ManipulationEvent& e : manipulator.events()) events.push_back(e.to_json(cloth));
  return events;
}

}  // namespace

RunOutcome run_scene(const Scene& scene, const std::filesystem::path& out_dir) {
  const IntegratorOptions options = read_integrator_options(scene.integrator, scene.file, "integrator");
  std::shared_ptr<const Dummy> dummy;
  if (!scene.dummy.is_null())
    dummy = std::make_shared<const Dummy>(make_dummy(scene.dummy, scene.file, "dummy", scene.base_dir));
  ClothSystem system(build_cloth(scene.cloth), dummy, scene.forces);
  for (const GridPoint& pin : scene.pins) {
    const int i = system.cloth().index(pin.row, pin.col);
    system.constraints().fix_at(i, system.cloth().rest_positions.segment<3>(3 * i));
  }
  Eigen::VectorXd y = system.initial_state(0.0);
  const Eigen::Index n3 = 3 * system.num_particles();
  system.project(0.0, y.head(n3), y.tail(n3));

  std::optional<HandInput> input;
  if (!scene.input.is_null())
    input = load_hand_input(scene.input, scene.file, "input", scene.base_dir);
  Manipulator manipulator(system, input ? &input->track : nullptr, scene.manipulation);
  if (auto changed = manipulator.update(0.0, y)) y = std::move(*changed);

  auto integrator = make_integrator(options, system);
  integrator->reset(0.0, y);

  std::filesystem::create_directories(out_dir);
  EnergyWriter energy_file(out_dir / "energy.csv");
  if (dummy) write_dummy_csv(out_dir / "dummy.csv", *dummy);
  std::optional<HandsWriter> hands_file;
  if (input) {
    hands_file.emplace(out_dir / "hands.csv");
    hands_file->write(0.0, manipulator.hands(0.0, y));
  }
  const EnergyBreakdown e0 = energy_of(system, y);
  energy_file.write(0.0, e0);
  FrameRecorder frames(scene.output, out_dir, system);
  frames.record(0.0, y, true);
  double drift_max_abs = 0.0;
  EnergyBreakdown e_last = e0;

  DivergenceCheck divergence(scene);
  divergence.account_for(system, e0);
  RunOutcome outcome{"ok", "", exit_ok, {}};
  const double interval = scene.output.energy_interval;
  long outputs_written = 0;  // output times are multiples of the interval, not running sums
  double next_output = interval;
  const auto wall_start = std::chrono::steady_clock::now();
  // Times within this of the end count as the end (fixed steps accumulate round-off).
  const double time_eps = 1e-12 * std::max(1.0, scene.duration);
  double t = 0.0;
  while (t < scene.duration - time_eps) {
    if (integrator->counters().steps >= options.max_steps) {
      outcome = {"failed", fmt::format("reached integrator.max_steps = {}", options.max_steps),
                 exit_diverged, {}};
      break;
    }
    double t_stop = std::min({interval > 0.0 ? next_output : scene.duration, scene.duration,
                              manipulator.next_key_time(t)});
    if (scene.duration - t_stop <= time_eps) t_stop = scene.duration;
    try {
      t = integrator->step(t_stop);
    } catch (const IntegratorFailure& failure) {
      outcome = {"failed", failure.flag() + ": " + failure.what(), exit_diverged, {}};
      break;
    }
    const std::string why = divergence.reason(system, t, integrator->state());
    if (!why.empty()) {
      outcome = {"diverged", why, exit_diverged, {}};
      break;
    }
    const auto changed = manipulator.update(t, integrator->state());
    if (changed) {
      integrator->reset(t, *changed);
      divergence.account_for(system, energy_of(system, *changed));
    }
    frames.record(t, integrator->state(), changed.has_value());
    if (interval == 0.0 || t >= next_output - time_eps || t >= scene.duration - time_eps) {
      e_last = energy_of(system, integrator->state());
      energy_file.write(t, e_last);
      if (hands_file) hands_file->write(t, manipulator.hands(t, integrator->state()));
      drift_max_abs = std::max(drift_max_abs, std::abs(e_last.total() - e0.total()));
      while (interval > 0.0 && next_output <= t + time_eps)
        next_output = static_cast<double>(++outputs_written + 1) * interval;
    }
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();

  const IntegratorCounters& counters = integrator->counters();
  nlohmann::json summary = {
      {"status", outcome.status},
      {"integrator", options.name},
      {"table", options.table},
      {"dt", options.dt},
      {"adaptive", options.adaptive},
      {"steps", counters.steps},
      {"sim_time", integrator->time()},
      {"duration", scene.duration},
      {"wall_seconds", wall},
      {"rhs_evals", counters.rhs_evals},
      {"counters", counters.to_json()},
      {"particles", system.num_particles()},
      {"springs", system.cloth().springs.size()},
      {"object_particles", dummy ? dummy->size() : 0},
      {"energy_initial", e0.total()},
      {"energy_final", e_last.total()},
      {"energy_drift_max_abs", drift_max_abs},
      {"energy_drift_max_rel", drift_max_abs / std::max(std::abs(e0.total()), 1e-300)},
      {"events", events_json(manipulator, system.cloth())},
      {"integrator_options", to_json(options)},
      {"scene", scene.source},
  };
  if (outcome.status != "ok") {
    summary["reason"] = outcome.reason;
    summary["time"] = integrator->time();
  } else {
    write_state_csv(out_dir / "state.csv", system, integrator->state());
  }
  write_json(out_dir / "summary.json", summary);
  outcome.summary = std::move(summary);
  return outcome;
}

}  // namespace drape
