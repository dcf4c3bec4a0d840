#include "integrators/explicit/leapfrog.hpp"

#include "integrators/explicit/kick_drift.hpp"

namespace drape {

void Leapfrog::reset(double t, const Eigen::VectorXd& y) {
  Integrator::reset(t, y);
  m_acceleration.resize(y.size() / 2);
  m_have_acceleration = false;
}

double Leapfrog::step(double t_stop) {
  const double t_next = fixed_step_end(m_dt, m_t, t_stop);
  const double h = t_next - m_t;
  VecMap x = positions(), v = velocities();
  VecMap a(m_acceleration.data(), m_acceleration.size());
  if (!m_have_acceleration) {
    m_system.acceleration(m_t, x, v, a);
    ++m_counters.rhs_evals;
  }
  // Each kick carries the collision force of its end of the step, so each is followed by the
  // Coulomb bound on that contact's tangential change (docs/model.md section 4.12): a particle
  // that sticks then drifts nowhere.
  const double half_h = 0.5 * h;
  kick_friction_drift(m_system, x, v, a, half_h, h);
  m_system.project(t_next, x, v);
  m_system.acceleration(t_next, x, v, a);
  ++m_counters.rhs_evals;
  kick_friction(m_system, x, v, a, half_h);  // v(n+1), synchronised; the next kick continues from here
  m_system.constraints().project(t_next, x, v);
  m_have_acceleration = true;
  return accept_fixed_step(t_next);
}

}  // namespace drape
