#include "integrators/interface/integrator.hpp"

#include <algorithm>
#include <limits>

namespace drape {

nlohmann::json IntegratorCounters::to_json() const {
  return {{"steps", steps},
          {"attempts", attempts},
          {"rhs_evals", rhs_evals},
          {"newton_iters", newton_iters},
          {"linear_iters", linear_iters},
          {"jacobian_setups", jacobian_setups},
          {"error_test_failures", error_test_failures},
          {"convergence_failures", convergence_failures},
          {"resets", resets},
          {"step_halvings", step_halvings},
          {"line_search_backtracks", line_search_backtracks},
          {"potential_decrease", potential_decrease},
          {"potential_rises", potential_rises}};
}

void IntegratorCounters::add_potential_change(double start, double end, double magnitude) {
  // E sums terms each rounded to about machine epsilon: a rise within 1e3 epsilon of their
  // magnitude is noise (the tolerance of the line search and of VBD's block steps).
  constexpr double round_off = 1e3 * std::numeric_limits<double>::epsilon();
  potential_decrease += start - end;
  if (end - start > round_off * magnitude) ++potential_rises;
}

void Integrator::reset(double t, const Eigen::VectorXd& y) {
  m_t = t;
  m_y = y;
  // The first call starts the run; every later one is a restart at an event.
  if (m_started) ++m_counters.resets;
  m_started = true;
}

double Integrator::accept_fixed_step(double t_next) {
  m_last_step = t_next - m_t;
  m_t = t_next;
  ++m_counters.steps;
  ++m_counters.attempts;
  return m_t;
}

void Integrator::check_attempts(long max_steps) const {
  if (m_counters.attempts >= max_steps)
    throw IntegratorFailure("max_steps", "reached integrator.max_steps = " +
                                             std::to_string(max_steps) +
                                             " step attempts at t = " + std::to_string(m_t));
}

double fixed_step_end(double dt, double t, double t_stop) {
  // A remainder within round-off of dt is taken as one full step, so that dt = 1/30 over 1 s
  // takes 30 steps, not 30 plus a sliver.
  return t_stop - t <= dt * (1.0 + 1e-9) ? t_stop : t + dt;
}

}  // namespace drape
