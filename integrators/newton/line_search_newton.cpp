#include "integrators/newton/line_search_newton.hpp"

#include <cmath>

namespace drape {

namespace {

// Armijo's sufficient-decrease constant (Nocedal and Wright 2006, section 3.1: 1e-4 is typical).
constexpr double armijo = 1e-4;
// 2^-30 ~ 1e-9 of the Newton step: below that the merit function's round-off decides.
constexpr int max_halvings = 30;

}  // namespace

LineSearchNewton::LineSearchNewton(const ClothSystem& system, ForceSplit split,
                                   ReducedNewtonSolver& solver)
    : m_system(system), m_potential(system, split), m_solver(solver) {}

StageSolve LineSearchNewton::solve(double t, double gamma, ConstVecRef a, VecRef z,
                                   const StageTolerance& stop) {
  StageSolve result;
  const Eigen::Index n3 = z.size() / 2;
  m_potential.begin_stage(t, gamma, a, z);
  ++result.rhs_evals;
  const double mass = m_system.particle_mass();
  m_rhs.setZero(z.size());
  m_step.resize(z.size());
  m_gradient.resize(n3);
  while (result.iterations < stop.max_iterations) {
    ++result.iterations;
    if (result.iterations > 1) m_potential.freeze_damping(z);
    m_potential.gradient(z, m_gradient);
    ++result.rhs_evals;
    // (I - gamma J) dz = [0; -M^-1 g] reduces to S dz_v = -g (reduced_newton_solver.hpp); the
    // fixed rows of r are zero, so fixed particles do not move.
    m_solver.update(z.head(n3), z.tail(n3), gamma);
    ++result.setups;
    m_rhs.tail(n3) = -m_gradient / mass;
    m_solver.solve(m_rhs, m_step);
    double slope = m_gradient.dot(m_step.tail(n3));
    if (!(slope < 0.0)) {
      // An unconverged CG may return no descent direction: fall back to steepest descent in the
      // metric M (S is positive definite, so the exact direction always descends).
      m_step.tail(n3) = -m_gradient / mass;
      slope = m_gradient.dot(m_step.tail(n3));
    }
    m_step.head(n3) = gamma * m_step.tail(n3);
    const double update_norm =
        std::sqrt((m_step.cwiseProduct(stop.weights)).squaredNorm() / static_cast<double>(z.size()));
    if (update_norm <= stop.tolerance) {
      // Within tolerance, the full Newton update is the better iterate (quadratic convergence).
      m_v = z.tail(n3) + m_step.tail(n3);
      m_potential.state_of(m_v, z);
      result.converged = true;
      return result;
    }
    if (slope == 0.0) return result;  // zero gradient with a step above tolerance: no progress
    if (!line_search(z, slope, result)) return result;
  }
  return result;
}

bool LineSearchNewton::line_search(VecRef z, double slope, StageSolve& result) {
  const Eigen::Index n3 = z.size() / 2;
  const double start = m_potential.value(z);
  m_trial = z;
  double alpha = 1.0;
  for (int k = 0; k <= max_halvings; ++k) {
    m_v = z.tail(n3) + alpha * m_step.tail(n3);
    m_potential.state_of(m_v, m_trial);
    if (m_potential.value(m_trial) <= start + armijo * alpha * slope) {
      z = m_trial;
      return true;
    }
    alpha *= 0.5;
    ++result.backtracks;
  }
  return false;
}

}  // namespace drape
