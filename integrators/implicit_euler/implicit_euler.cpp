#include "integrators/implicit_euler/implicit_euler.hpp"

namespace drape {

ImplicitEuler::ImplicitEuler(ClothSystem& system, const IntegratorOptions& options)
    : Integrator(system),
      m_dt(options.dt),
      m_solver(system, *reduced_solve_named(linear_solver_of(options)), ForceSplit::all,
               linear_tolerance_of(options), options.max_linear_iters) {}

double ImplicitEuler::step(double t_stop) {
  const double t_next = fixed_step_end(m_dt, m_t, t_stop);
  const double h = t_next - m_t;
  VecMap x = positions(), v = velocities();
  const Eigen::Index n3 = x.size();
  // One Newton step of y_{n+1} = y_n + h f(y_{n+1}) from y_n solves (I - h J) dy = h f(y_n);
  // its reduction to the velocities is Baraff and Witkin's system. A fixed particle's rows are
  // the identity, so its increment is set to the exact prescribed motion instead.
  m_residual.resize(m_y.size());
  m_system.rhs(m_t, m_y, m_residual);
  ++m_counters.rhs_evals;
  m_residual *= h;
  const ConstraintSet& constraints = m_system.constraints();
  for (const int i : constraints.fixed_particles()) {
    const Trajectory& path = *constraints.trajectory(i);
    m_residual.segment<3>(3 * i) = path.position(m_t + h) - particle(x, i);
    m_residual.segment<3>(n3 + 3 * i) = path.velocity(m_t + h) - particle(v, i);
  }
  m_solver.update(x, v, h);
  ++m_counters.jacobian_setups;
  m_increment.resize(m_y.size());
  const long cg_before = m_solver.iterations();
  // The last step's dv starts CG: velocities change smoothly from step to step.
  if (!m_solver.solve(m_residual, m_increment, CgStart::previous)) ++m_counters.convergence_failures;
  m_counters.linear_iters += m_solver.iterations() - cg_before;
  ++m_counters.newton_iters;
  m_y += m_increment;  // x += h (v + dv), v += dv
  m_system.project(t_next, x, v);
  return accept_fixed_step(t_next);
}

}  // namespace drape
