#include "integrators/symplectic_euler.hpp"

namespace drape {

void SymplecticEuler::reset(double t, const Eigen::VectorXd& y) {
  Integrator::reset(t, y);
  m_acceleration.resize(y.size() / 2);
}

double SymplecticEuler::step(double t_stop) {
  const double h = fixed_step_size(m_dt, m_t, t_stop);
  VecMap x = positions(), v = velocities();
  VecMap a(m_acceleration.data(), m_acceleration.size());
  m_system.acceleration(m_t, x, v, a);
  ++m_counters.rhs_evals;
  v += h * a;
  x += h * v;
  m_t += h;
  m_system.project(m_t, x, v);
  m_last_step = h;
  ++m_counters.steps;
  ++m_counters.attempts;
  return m_t;
}

}  // namespace drape
