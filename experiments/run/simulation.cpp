#include "experiments/run/simulation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>

#include "experiments/run/initial_perturbation.hpp"

namespace drape {

namespace {

// Times within this of the end count as the end (fixed steps accumulate round-off).
double end_tolerance(double duration) { return 1e-12 * std::max(1.0, duration); }

// CPU time of the process, every thread's (POSIX clock_gettime, CLOCK_PROCESS_CPUTIME_ID).
double process_cpu_seconds() {
  timespec now{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

}  // namespace

Simulation::Simulation(ClothSystem& system, Manipulator& manipulator, Integrator& integrator,
                       const SimulationSettings& settings, Eigen::VectorXd y0)
    : m_system(system),
      m_manipulator(manipulator),
      m_integrator(integrator),
      m_settings(settings),
      m_divergence(system.params().gravity.norm(),
                   std::max(settings.duration, settings.runaway_horizon)) {
  const Eigen::Index n3 = 3 * static_cast<Eigen::Index>(system.num_particles());
  system.project(0.0, y0.head(n3), y0.tail(n3));
  if (auto changed = manipulator.update(0.0, y0)) y0 = std::move(*changed);
  perturb_new_maps(y0);
  integrator.reset(0.0, y0);
  m_divergence.account_for(system, energy_of(system, y0));
}

void Simulation::add_observer(SimulationObserver& observer) {
  m_observers.push_back(&observer);
  m_keep_step_ends = m_keep_step_ends || observer.interpolates();
}

bool Simulation::advance(double t_until, const std::function<bool()>& keep_going) {
  const auto wall_start = std::chrono::steady_clock::now();
  const double cpu_start = process_cpu_seconds();
  const double observed_before = m_observer_seconds;
  const double observed_cpu_before = m_observer_cpu_seconds;
  if (!m_started) {
    m_started = true;
    notify([&](SimulationObserver& o) { o.on_start(*this); });
  }
  const double eps = end_tolerance(m_settings.duration);
  const double target = std::min(t_until, m_settings.duration);
  while (!m_status.ended() && m_t < target - eps && (!keep_going || keep_going())) take_step();
  if (!m_status.ended() && at_end()) {
    list_unplayed_keys();
    end("ok", "");
  }
  // The observers' time is theirs, not the method's (the restart error's branches take seconds).
  m_wall_seconds +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count() -
      (m_observer_seconds - observed_before);
  m_cpu_seconds += process_cpu_seconds() - cpu_start - (m_observer_cpu_seconds - observed_cpu_before);
  return !m_status.ended();
}

const RunStatus& Simulation::run(const std::function<bool()>& keep_going) {
  advance(m_settings.duration, keep_going);
  return m_status;
}

void Simulation::branch_from(const Simulation& other) {
  m_system.constraints() = other.m_system.constraints();
  m_manipulator.copy_state_from(other.m_manipulator);
  m_maps = other.m_maps;  // the maps it perturbed are in the copied state
  m_t = m_t0 = other.time();
  const Eigen::VectorXd& y = other.state();
  if (m_keep_step_ends) m_y0 = m_y1 = y;
  m_integrator.reset(m_t, y);
  m_divergence.account_for(m_system, energy_of(m_system, y));
  m_status = RunStatus{};
}

void Simulation::set_state(Eigen::VectorXd y) {
  const Eigen::Index n3 = y.size() / 2;
  m_system.project(m_t, y.head(n3), y.tail(n3));
  if (m_keep_step_ends) m_y0 = m_y1 = y;
  m_integrator.reset(m_t, y);
  m_divergence.account_for(m_system, energy_of(m_system, y));
}

bool Simulation::at_end() const { return m_t >= m_settings.duration - end_tolerance(m_settings.duration); }

double Simulation::next_landing_time() const {
  const double duration = m_settings.duration;
  double t_stop = std::min(duration, m_manipulator.next_key_time(m_t));
  if (duration - t_stop <= end_tolerance(duration)) t_stop = duration;
  const double clock = m_settings.time_grid;
  if (m_settings.adaptive || clock <= 0.0) return t_stop;
  // The clock tick a full step reaches within round-off, if any (SimulationSettings).
  const double reach = m_t + m_settings.dt;
  const double tolerance = 1e-9 * m_settings.dt;
  const double k = std::floor(reach / clock);
  for (const double tick : {k * clock, (k + 1.0) * clock})
    if (tick > m_t && tick < t_stop && std::abs(tick - reach) <= tolerance) return tick;
  return t_stop;
}

void Simulation::take_step() {
  if (m_integrator.counters().steps >= m_settings.max_steps) {
    end("failed", fmt::format("reached integrator.max_steps = {}", m_settings.max_steps));
    return;
  }
  const double t_stop = next_landing_time();
  m_t0 = m_t;
  if (m_keep_step_ends) m_y0 = m_integrator.state();
  try {
    m_t = m_integrator.step(t_stop);
  } catch (const IntegratorFailure& failure) {
    end("failed", failure.flag() + ": " + failure.what());
    return;
  }
  const double h = m_t - m_t0;
  if (!(h > 0.0)) {  // the input checks rule this out; a loop that cannot advance must not spin
    end("failed", fmt::format("a step from t = {} did not advance time", m_t0));
    return;
  }
  m_min_step = m_integrator.counters().steps == 1 ? h : std::min(m_min_step, h);
  m_max_step = std::max(m_max_step, h);
  const std::string why = m_divergence.reason(m_system, m_t, m_integrator.state());
  if (!why.empty()) {
    end("diverged", why);
    return;
  }
  if (m_keep_step_ends) m_y1 = m_integrator.state();
  auto changed = m_manipulator.update(m_t, m_integrator.state());
  if (changed) {
    perturb_new_maps(*changed);
    m_integrator.reset(m_t, *changed);
    m_divergence.account_for(m_system, energy_of(m_system, *changed));
  }
  notify([&](SimulationObserver& o) { o.on_step(*this, changed.has_value()); });
}

void Simulation::perturb_new_maps(Eigen::VectorXd& y) {
  if (!m_settings.perturbation.after_map) return;
  long maps = 0;
  for (const ManipulationEvent& e : m_manipulator.events()) maps += e.type == "map";
  while (m_maps < maps)
    perturb_positions(m_settings.perturbation, static_cast<std::uint64_t>(++m_maps),
                      m_settings.spacing, m_system.constraints(), y);
}

template <class Call>
void Simulation::notify(Call&& call) {
  if (m_observers.empty()) return;
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start = process_cpu_seconds();
  for (SimulationObserver* o : m_observers) call(*o);
  m_observer_seconds +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  m_observer_cpu_seconds += process_cpu_seconds() - cpu_start;
}

void Simulation::end(std::string status, std::string reason) {
  m_status = {std::move(status), std::move(reason)};
  notify([&](SimulationObserver& o) { o.on_end(*this); });
}

Eigen::VectorXd Simulation::interpolate(double t) const {
  const double h = m_t - m_t0;
  if (!m_keep_step_ends || h <= 0.0) return m_integrator.state();
  const double s = std::clamp((t - m_t0) / h, 0.0, 1.0);
  const double s2 = s * s, s3 = s2 * s;
  // Cubic Hermite basis on [0, 1] and its derivative (positions from x and h v at both ends).
  const double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2,
               h11 = s3 - s2;
  const double d00 = 6 * s2 - 6 * s, d10 = 3 * s2 - 4 * s + 1, d01 = -d00, d11 = 3 * s2 - 2 * s;
  const Eigen::Index n3 = m_y0.size() / 2;
  const auto x0 = m_y0.head(n3), v0 = m_y0.tail(n3), x1 = m_y1.head(n3), v1 = m_y1.tail(n3);
  Eigen::VectorXd y(m_y0.size());
  y.head(n3) = h00 * x0 + (h10 * h) * v0 + h01 * x1 + (h11 * h) * v1;
  y.tail(n3) = (d00 / h) * x0 + d10 * v0 + (d01 / h) * x1 + d11 * v1;
  return y;
}

}  // namespace drape
