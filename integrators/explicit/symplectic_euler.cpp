#include "integrators/explicit/symplectic_euler.hpp"

#include "integrators/explicit/kick_drift.hpp"

namespace drape {

void SymplecticEuler::reset(double t, const Eigen::VectorXd& y) {
  Integrator::reset(t, y);
  m_acceleration.resize(y.size() / 2);
}

double SymplecticEuler::step(double t_stop) {
  const double t_next = fixed_step_end(m_dt, m_t, t_stop);
  const double h = t_next - m_t;
  VecMap x = positions(), v = velocities();
  VecMap a(m_acceleration.data(), m_acceleration.size());
  m_system.acceleration(m_t, x, v, a);
  ++m_counters.rhs_evals;
  kick_friction_drift(m_system, x, v, a, h, h);  // docs/model.md section 4.12
  m_system.project(t_next, x, v);
  return accept_fixed_step(t_next);
}

}  // namespace drape
