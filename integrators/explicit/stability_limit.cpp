#include "integrators/explicit/stability_limit.hpp"

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

namespace drape {

ExplicitStabilityLimit explicit_stability_limit(const ClothSystem& system, ConstVecRef x,
                                                ConstVecRef v, int max_iterations) {
  const Eigen::Index n3 = x.size();
  const ConstraintSet& constraints = system.constraints();
  const double mass = system.particle_mass();
  // A fixed seed: the same state gives the same answer.
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Eigen::VectorXd u(n3), w(n3);
  for (Eigen::Index k = 0; k < n3; ++k) u[k] = uniform(rng);
  constraints.zero_fixed(u);
  u.normalize();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n3);
  const auto stiffness_times = [&](const Eigen::VectorXd& in, Eigen::VectorXd& out) {
    system.force_jacobian_times(x, v, in, zero, out, false);  // fixed rows zeroed
    out /= -mass;
  };
  ExplicitStabilityLimit limit;
  double lambda = 0.0;  // the Rayleigh quotient u' A u, omega^2 once it settles
  for (double previous = 0.0;; previous = lambda) {
    if (++limit.iterations > max_iterations)
      throw std::runtime_error("explicit_stability_limit: the power iteration did not settle");
    stiffness_times(u, w);
    lambda = u.dot(w);
    const double norm = w.norm();
    if (norm == 0.0) break;  // no stiffness at all: no limit from the springs
    u = w / norm;
    if (std::abs(lambda - previous) <= 1e-10 * std::abs(lambda)) break;
  }
  system.force_jacobian_times(x, v, zero, u, w, false);
  limit.damping_rate = 0.0 - u.dot(w) / mass;  // +0, not -0, without damping
  limit.omega = std::sqrt(std::max(lambda, 0.0));
  const double c = limit.damping_rate, none = std::numeric_limits<double>::infinity();
  limit.undamped = limit.omega > 0.0 ? 2.0 / limit.omega : none;
  // The positive root of h^2 omega^2 + 2 h c - 4 = 0.
  limit.damped = lambda > 0.0 ? (-c + std::sqrt(c * c + 4.0 * lambda)) / lambda : none;
  return limit;
}

}  // namespace drape
