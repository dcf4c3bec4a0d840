#pragma once
// One interface for every time integrator. An integrator steps a ClothSystem; it knows nothing of
// manipulations: events change the constraints between steps and call reset().
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "core/model/cloth_system.hpp"

namespace drape {

/// Work counters every integrator reports, with the same meaning everywhere.
struct IntegratorCounters {
  long steps = 0;                 ///< accepted steps
  long attempts = 0;              ///< attempted steps (accepted + rejected)
  long rhs_evals = 0;             ///< right-hand side (force) evaluations
  long newton_iters = 0;          ///< nonlinear iterations
  long linear_iters = 0;          ///< Krylov / CG iterations
  long jacobian_setups = 0;       ///< Jacobian or preconditioner (re)builds
  long error_test_failures = 0;   ///< steps rejected by the error test
  long convergence_failures = 0;  ///< nonlinear or linear solver failures
  long resets = 0;                ///< restarts at events
  long step_halvings = 0;         ///< fixed steps retried as two halves after a solver failure
  long line_search_backtracks = 0;  ///< step halvings of the stage solves' line search
  /// Methods that minimise backward Euler's incremental potential E (projective-dynamics, vbd,
  /// implicit-euler and bdf2 with solve = converged; 0 for the others): the sum over steps of
  /// E at the step's start guess minus E at its final iterate [J] (docs/outputs.md, "Counters").
  double potential_decrease = 0.0;
  /// Those methods' steps whose final iterate's E is above the start guess's, beyond round-off.
  long potential_rises = 0;

  /// Books one step's E at its start guess and final iterate; `magnitude` is the sum of E's
  /// terms' absolute values (at either point), which bounds the round-off of their difference.
  void add_potential_change(double start, double end, double magnitude);
  nlohmann::json to_json() const;
};

/// A step that could not be taken (solver failure); `flag` is e.g. the ARKODE flag name.
class IntegratorFailure : public std::runtime_error {
 public:
  IntegratorFailure(std::string flag, const std::string& message)
      : std::runtime_error(message), m_flag(std::move(flag)) {}
  const std::string& flag() const { return m_flag; }

 private:
  std::string m_flag;
};

/// Time integrator of the constrained cloth ODE.
class Integrator {
 public:
  explicit Integrator(ClothSystem& system) : m_system(system) {}
  virtual ~Integrator() = default;
  Integrator(const Integrator&) = delete;
  Integrator& operator=(const Integrator&) = delete;

  /// (Re)starts at time t from state y, discarding any history (docs/model.md section 5: reset at
  /// events).
  virtual void reset(double t, const Eigen::VectorXd& y);
  /// Takes one step that does not pass t_stop, projects, and returns the new time.
  virtual double step(double t_stop) = 0;

  double time() const { return m_t; }
  /// State at time(), velocities synchronised with positions.
  const Eigen::VectorXd& state() const { return m_y; }
  const IntegratorCounters& counters() const { return m_counters; }
  /// Size of the last step taken.
  double last_step() const { return m_last_step; }

 protected:
  /// Books an accepted fixed step that ended at t_next (time, step size, counters); returns it.
  double accept_fixed_step(double t_next);
  /// Throws IntegratorFailure ("max_steps") once the attempts reach `max_steps`: a fixed step
  /// halved after failed solves could otherwise take 2^max_step_halvings attempts inside one
  /// step() call, out of reach of the simulation's check between calls.
  void check_attempts(long max_steps) const;

  /// Views of the position and velocity blocks of m_y.
  VecMap positions() { return VecMap(m_y.data(), m_y.size() / 2); }
  VecMap velocities() { return VecMap(m_y.data() + m_y.size() / 2, m_y.size() / 2); }

  ClothSystem& m_system;
  double m_t = 0.0;
  double m_last_step = 0.0;
  bool m_started = false;
  Eigen::VectorXd m_y;
  IntegratorCounters m_counters;
};

/// End time of a fixed step of size dt from t: exactly t_stop when it is within reach, so that
/// runs land on output, event and end times without round-off.
double fixed_step_end(double dt, double t, double t_stop);

}  // namespace drape
