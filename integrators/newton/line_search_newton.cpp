#include "integrators/newton/line_search_newton.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace drape {

namespace {

// Armijo's sufficient-decrease constant (Nocedal and Wright 2006, section 3.1: 1e-4 is typical).
constexpr double armijo = 1e-4;
// 2^-30 ~ 1e-9 of the Newton step: below that the merit function's round-off decides.
constexpr int max_halvings = 30;
// E_k is a sum of terms each rounded to about machine epsilon: a change below 1e3 epsilon of
// their magnitude is noise (the sheet's E_k sums 144 particles' and 506 springs' terms).
constexpr double round_off = 1e3 * std::numeric_limits<double>::epsilon();
// The first iteration's and the largest relative residual of the Hessian solve. Caps of 0.5 and
// 0.1 (Eisenstat and Walker use 0.9) cost step halvings on the swinging sheet and the drape
// scenes (docs/journal/2026-11-25-newton-iteration-cost.md).
constexpr double max_forcing = 1e-2;
// The Levenberg-Marquardt shift of the exact Jacobian, in units of M (More 1978, "The
// Levenberg-Marquardt algorithm: implementation and theory"; Nocedal and Wright 2006, section
// 4.3): where A + shift M gives no descent it grows tenfold from `min_shift`; after a full step
// it shrinks threefold, to zero below `min_shift`, so that a definite A keeps Newton's quadratic
// convergence, and after a backtracked step it grows tenfold. |M^-1 A| is of the order of 8
// gamma^2 k / m (the stencil's neighbours), about 1e6 for the 64 x 64 sheet at 100x stiffness
// and 1/30 s; while it is below `max_shift` / 3, the direction of A + max_shift M is within
// 50 % of -g / (max_shift m) and descends. A singular factorisation grows the shift too, so S
// is a fallback the loop reaches only beyond that (at most 12 factorisations an iteration).
constexpr double min_shift = 1e-3;
constexpr double max_shift = 1e8;
constexpr double shift_growth = 10.0;
constexpr double shift_decay = 3.0;
// ExactSolve::bicgstab: BiCGSTAB iterations before the direction falls back to the LU. Most
// local-phase systems of Alexander's SDIRK2 on the 64 x 64 sheet at 1/30 s converge in 3-15
// iterations, a few near a buckling point take 70 to over 200; bounds of 15 and 20 kept the
// LU's Newton path (9 iterations a step), 30 and 200 lengthened it (27 and 20), 10 factorised
// more often (docs/journal/2026-11-28-bicgstab-exact-direction.md).
constexpr int max_krylov_iterations = 20;

// The forcing term of an inexact Newton iteration (Eisenstat and Walker 1996, SIAM J. Sci.
// Comput. 17(1), choice 2): CG solves S d = -g only to |g + S d| <= eta |g|, with eta = 0.9
// (|g_k| / |g_k-1|)^2. Far from the root, where the line search cuts the step anyway, a few CG
// iterations give a direction as good as an exact solve; as |g| falls quadratically eta falls
// with it, which keeps the exact Newton's convergence. Their safeguard (eta at least 0.9
// eta_k-1^2 when that exceeds 0.1) never applies under the cap. `floor` is the solver's own
// tolerance; a linear_tolerance above the cap is the user's to choose and wins.
double forcing_term(double gradient_norm, double previous_norm, double floor) {
  if (previous_norm == 0.0) return std::max(max_forcing, floor);
  const double ratio = gradient_norm / previous_norm;
  return std::max(std::min(0.9 * ratio * ratio, max_forcing), floor);
}

}  // namespace

std::optional<ExactSolve> exact_solve_named(const std::string& name) {
  if (name == "lu") return ExactSolve::lu;
  if (name == "bicgstab") return ExactSolve::bicgstab;
  return std::nullopt;
}

std::string exact_solve_names() { return "lu, bicgstab"; }

LineSearchNewton::LineSearchNewton(const ClothSystem& system, ForceSplit split,
                                   ReducedNewtonSolver& solver, ExactSolve exact_solve)
    : m_system(system),
      m_potential(system, split),
      m_solver(solver),
      m_exact(system, split),
      m_exact_solve(exact_solve),
      // S's preconditioner from the last global-phase iterate: A differs from S by the terms S
      // drops, small next to M where gamma h is (docs/integrators/line-search-newton.md, "Newton
      // direction").
      m_precondition([this](const Eigen::VectorXd& r, Eigen::VectorXd& out) {
        m_solver.precondition(r, out);
      }) {}

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
  double previous_norm = 0.0, rate = 0.0;
  double previous_gradient_norm = 0.0;
  bool local = false;  // the last line search took the full step
  double shift = 0.0;  // Levenberg-Marquardt shift of A in the local phase, in units of M
  while (result.iterations < stop.max_iterations) {
    ++result.iterations;
    if (result.iterations > 1) m_potential.freeze_damping(z);
    m_potential.gradient(z, m_gradient);
    ++result.rhs_evals;
    // Near the solution (the last line search took the full step) the exact Jacobian's Newton
    // direction, when it descends, converges quadratically; elsewhere, and when it does not
    // descend, the definite S gives a descent direction from any iterate.
    double slope = 0.0;
    bool exact = false;
    const double gradient_norm = m_gradient.norm();
    const double forcing = forcing_term(gradient_norm, previous_gradient_norm, m_solver.tolerance());
    // BiCGSTAB's local-phase solves stop at max_forcing, not at Eisenstat and Walker's term,
    // which falls with |g|^2 to 1e-3 and below there: the Newton path stayed the same on the
    // 64 x 64 sheet (9 its a step) and within 1.4 % on the drape scene for 7-37 % fewer Krylov
    // iterations (docs/journal/2026-11-28-bicgstab-exact-direction.md). The LU ignores it.
    if (local)
      exact = shifted_exact_direction(z, gamma, std::max(max_forcing, m_solver.tolerance()), shift,
                                      slope, result);
    if (exact) {
      m_step.tail(n3) = m_direction;
    } else {
      // (I - gamma J) dz = [0; -M^-1 g] reduces to S dz_v = -g (reduced_newton_solver.hpp);
      // the fixed rows of r are zero, so fixed particles do not move.
      m_solver.update(z.head(n3), z.tail(n3), gamma);
      ++result.setups;
      m_rhs.tail(n3) = -m_gradient / mass;
      m_solver.solve(m_rhs, m_step, CgStart::zero, forcing);
      slope = m_gradient.dot(m_step.tail(n3));
      if (!(slope < 0.0)) {
        // An unconverged CG may return no descent direction: fall back to steepest descent in
        // the metric M (S is positive definite, so the exact direction always descends).
        m_step.tail(n3) = -m_gradient / mass;
        slope = m_gradient.dot(m_step.tail(n3));
      }
    }
    m_step.head(n3) = gamma * m_step.tail(n3);
    const double update_norm =
        std::sqrt((m_step.cwiseProduct(stop.weights)).squaredNorm() / static_cast<double>(z.size()));
    // The error left after applying this update, from the iteration's observed rate (ARKODE's
    // crate with its crdown 0.3, arkStep_NlsConvTest). Steps along the definite S converge
    // linearly (rates 0.6-0.9 measured on the swinging sheet), and an update of size d then
    // leaves about d rate / (1 - rate), more than ARKODE's min(rate, 1) d, which assumes
    // Newton's fast convergence. The first update is tested alone, as ARKODE does with its
    // initial rate 1.
    if (result.iterations > 1) rate = std::max(0.3 * rate, update_norm / previous_norm);
    previous_norm = update_norm;
    previous_gradient_norm = gradient_norm;
    const double error =
        result.iterations == 1 ? update_norm
        : rate < 1.0          ? update_norm * rate / (1.0 - rate)
                              : std::numeric_limits<double>::infinity();
    if (error <= stop.tolerance) {
      // Within tolerance, the full Newton update is the better iterate.
      m_v = z.tail(n3) + m_step.tail(n3);
      m_potential.state_of(m_v, z);
      result.converged = true;
      return result;
    }
    if (slope == 0.0) {  // zero gradient with a step above tolerance: no progress
      result.stopped_by = "a zero gradient with the update above tolerance";
      return result;
    }
    const long backtracks = result.backtracks;
    if (!line_search(z, slope, result)) {
      result.stopped_by = "the line search (no decrease of the incremental potential in 30 halvings)";
      return result;
    }
    local = result.backtracks == backtracks;
    if (exact)
      shift = !local                            ? std::max(min_shift, shift * shift_growth)
              : shift / shift_decay < min_shift ? 0.0
                                                : shift / shift_decay;
  }
  return result;
}

bool LineSearchNewton::shifted_exact_direction(ConstVecRef z, double gamma, double forcing,
                                               double& shift, double& slope, StageSolve& result) {
  const Eigen::Index n3 = z.size() / 2;
  for (;;) {
    ++result.setups;
    m_exact.form(z.head(n3), z.tail(n3), gamma, shift);
    bool solved = m_exact_solve == ExactSolve::bicgstab &&
                  m_exact.krylov_direction(m_gradient, m_direction, m_precondition, forcing,
                                           max_krylov_iterations, result.krylov_iterations);
    if (!solved && m_exact.factorize()) {  // the LU: by choice, or where BiCGSTAB fell short
      m_exact.newton_direction(m_gradient, m_direction);
      solved = true;
    }
    if (solved) {
      slope = m_gradient.dot(m_direction);
      if (slope < 0.0) {
        if (shift > 0.0) ++result.shifted_directions;
        return true;
      }
    }
    if (shift >= max_shift) return false;
    shift = std::max(min_shift, shift * shift_growth);
  }
}

bool LineSearchNewton::line_search(VecRef z, double slope, StageSolve& result) {
  const Eigen::Index n3 = z.size() / 2;
  double magnitude = 0.0;
  const double start = m_potential.value(z, magnitude);
  m_trial = z;
  m_v = z.tail(n3) + m_step.tail(n3);
  m_potential.state_of(m_v, m_trial);
  // A decrease below E_k's round-off cannot be measured: the full Newton step is taken (near
  // the solution, where it is the best step there is). Without this, tight tolerances (rtol
  // 1e-8 and below) ended stages in 30 halvings that the merit's round-off decided.
  if (-slope <= round_off * magnitude) {
    z = m_trial;
    return true;
  }
  double alpha = 1.0;
  for (int k = 0; k <= max_halvings; ++k) {
    if (k > 0) {
      m_v = z.tail(n3) + alpha * m_step.tail(n3);
      m_potential.state_of(m_v, m_trial);
    }
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
