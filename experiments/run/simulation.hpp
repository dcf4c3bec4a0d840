#pragma once
// The one step/event loop of drapelab (docs/model.md section 5, docs/outputs.md "Steps and
// output times"): an integrator steps the model, the manipulator applies events between steps,
// the integrator is reset where an event changed the state, and a divergence check ends runs
// that no motion of the scene could reach. `drapelab run`, the experiments, the live mode and
// the tests all step through it. Observers (the writers) see every step and never change one.
#include <Eigen/Core>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "core/manipulations/manipulations.hpp"
#include "core/scene/scene.hpp"
#include "experiments/run/divergence_check.hpp"
#include "integrators/interface/integrator.hpp"

namespace drape {

class Simulation;

/// Watches a simulation. Called once at the start (after the events at t = 0), after every
/// accepted step, and once at the end; reads the simulation, never changes it.
class SimulationObserver {
 public:
  virtual ~SimulationObserver() = default;
  virtual void on_start(const Simulation& simulation) = 0;
  /// After a step that ended at simulation.time(); `event` when an event changed the state
  /// there (simulation.state() is the state after the event).
  virtual void on_step(const Simulation& simulation, bool event) = 0;
  virtual void on_end(const Simulation& /*simulation*/) {}
  /// True when the observer samples between step ends (Simulation::interpolate), so that the
  /// simulation keeps each step's two end states.
  virtual bool interpolates() const { return false; }
};

/// What the loop needs besides the model: when to stop and how the integrator steps.
struct SimulationSettings {
  double duration = 0.0;  ///< end time [s]
  /// The free fall the runaway bound allows for [s]; the duration when smaller (DivergenceCheck).
  double runaway_horizon = 0.0;
  long max_steps = std::numeric_limits<long>::max();
  bool adaptive = false;  ///< the integrator chooses its steps
  double dt = 0.0;        ///< fixed step [s] (ignored when adaptive)
  /// Time grid [s] (0 = none): a fixed step that ends within 1e-9 dt of a multiple of it ends
  /// exactly there, so that t = 0.01, 0.02, ... print as decimals instead of sums of dt. It moves
  /// a step by round-off only, and it depends on nothing a run writes: output intervals never
  /// change a step (docs/outputs.md, "Steps and output times").
  double time_grid = 0.01;
  /// With `after_map`, the free particles are perturbed right after each map (an ensemble's
  /// repeats would be identical after it otherwise; docs/experiments.md, "Ensembles").
  Perturbation perturbation;
  double spacing = 0.0;  ///< cloth.spacing, the perturbation's unit [m]
};

/// How a run ended: `running`, `ok`, `diverged` (non-finite or runaway state) or `failed` (a
/// solver could not take a step, or max_steps was reached).
struct RunStatus {
  std::string status = "running";
  std::string reason;
  bool ended() const { return status != "running"; }
};

/// Steps the constrained cloth ODE through a scene's events.
class Simulation {
 public:
  /// Projects `y0` at t = 0, applies the events due at t = 0 and starts `integrator` there.
  /// The model, manipulator and integrator must outlive the simulation.
  Simulation(ClothSystem& system, Manipulator& manipulator, Integrator& integrator,
             const SimulationSettings& settings, Eigen::VectorXd y0);

  /// Watches every later step; call before the first advance().
  void add_observer(SimulationObserver& observer);
  /// Steps until simulated time `t_until` (at most the duration) or until the run ends, landing
  /// only on key times and the end, or until `keep_going` (asked before each step, when given)
  /// says no. The steps do not depend on where an advance stops, so pausing changes nothing.
  /// Returns false once the run has ended.
  bool advance(double t_until, const std::function<bool()>& keep_going = nullptr);
  /// Runs to the end of the scene and returns how it ended.
  /// Advances to the end, or until keep_going (when given) says no: the status is then not
  /// ended.
  const RunStatus& run(const std::function<bool()>& keep_going = nullptr);
  /// Continues from `other`, a simulation of the same scene: its time, state, fixed particles
  /// and manipulation progress; this integrator restarts there and the status is `running`
  /// again. `other` is only read (a branch of the reference, reference_restarts.hpp).
  void branch_from(const Simulation& other);
  /// Keeps each step's two end states so that interpolate() works without an interpolating
  /// observer; it never changes a step.
  void keep_step_ends() { m_keep_step_ends = true; }
  /// Replaces the state at time() (a program that sets positions or velocities, docs/python.md):
  /// projected as the start state is, and the integrator restarts there as at an event.
  void set_state(Eigen::VectorXd y);

  double time() const { return m_t; }
  /// The state at time(), after any event applied there.
  const Eigen::VectorXd& state() const { return m_integrator.state(); }
  /// The state at any t in [previous step's start, time()]: the cubic Hermite interpolant of
  /// positions and velocities at the step's two ends (exact at both ends; before the event at
  /// time() when there was one). Every integrator is sampled alike through it.
  Eigen::VectorXd interpolate(double t) const;
  /// Start time of the last step.
  double step_start() const { return m_t0; }
  /// True once time() has reached the duration.
  bool at_end() const;

  const RunStatus& status() const { return m_status; }
  const ClothSystem& system() const { return m_system; }
  const Manipulator& manipulator() const { return m_manipulator; }
  /// Lists the input's keys not played so far as ignored at the current time, as the end of a
  /// run does (a live run stopped before its end; keys pressed after an end).
  void list_unplayed_keys() { m_manipulator.ignore_keys_after(m_t); }
  const Integrator& integrator() const { return m_integrator; }
  const SimulationSettings& settings() const { return m_settings; }
  /// Smallest and largest step taken (0 before the first step).
  double min_step() const { return m_min_step; }
  double max_step() const { return m_max_step; }
  /// Wall-clock seconds spent in advance(), the observers' calls excluded.
  double wall_seconds() const { return m_wall_seconds; }
  /// CPU seconds of this process (all its threads) over the same region as wall_seconds(): on a
  /// shared machine the cost a run would have alone, where wall time also counts the waits.
  double cpu_seconds() const { return m_cpu_seconds; }

 private:
  double next_landing_time() const;
  void take_step();
  void end(std::string status, std::string reason);
  /// Applies perturbation.after_map for every map the manipulator made since the last call.
  void perturb_new_maps(Eigen::VectorXd& y);
  /// Calls every observer, timing them (wall_seconds() and cpu_seconds() leave them out).
  template <class Call>
  void notify(Call&& call);

  ClothSystem& m_system;
  Manipulator& m_manipulator;
  Integrator& m_integrator;
  SimulationSettings m_settings;
  DivergenceCheck m_divergence;
  std::vector<SimulationObserver*> m_observers;
  RunStatus m_status;
  bool m_started = false;
  bool m_keep_step_ends = false;  ///< an observer interpolates
  double m_t = 0.0;
  double m_t0 = 0.0;
  Eigen::VectorXd m_y0;  ///< the last step's start state
  Eigen::VectorXd m_y1;  ///< the last step's end state, before any event
  double m_min_step = 0.0;
  double m_max_step = 0.0;
  double m_wall_seconds = 0.0;
  double m_observer_seconds = 0.0;
  double m_cpu_seconds = 0.0;
  double m_observer_cpu_seconds = 0.0;
  long m_maps = 0;  ///< maps perturbed so far
};

}  // namespace drape
