#include "integrators/newton/linearised_step.hpp"

namespace drape {

void LinearisedStep::take(double t, double h, double gamma, const Eigen::VectorXd* known,
                          Eigen::VectorXd& y, IntegratorCounters& counters) {
  const double t_next = t + h;
  const Eigen::Index n3 = y.size() / 2;
  const ConstVecMap x(y.data(), n3), v(y.data() + n3, n3);
  m_residual.resize(y.size());
  m_system.rhs(t, y, m_residual);
  ++counters.rhs_evals;
  m_residual *= gamma;
  if (known) m_residual += *known;
  const ConstraintSet& constraints = m_system.constraints();
  for (const int i : constraints.fixed_particles()) {
    const Trajectory& path = *constraints.trajectory(i);
    m_residual.segment<3>(3 * i) = path.position(t_next) - particle(x, i);
    m_residual.segment<3>(n3 + 3 * i) = path.velocity(t_next) - particle(v, i);
  }
  m_solver.update(x, v, gamma);
  ++counters.jacobian_setups;
  m_increment.resize(y.size());
  const long cg_before = m_solver.iterations();
  // CG starts from the best combination of the last two steps' dv: velocities change smoothly
  // from step to step, but the last dv alone is a poor start where the motion turns.
  if (!m_solver.solve(m_residual, m_increment, CgStart::projected))
    ++counters.convergence_failures;
  counters.linear_iters += m_solver.iterations() - cg_before;
  ++counters.newton_iters;
  y += m_increment;  // x += gamma (v + dv) + d_x, v += dv + d_v
}

}  // namespace drape
