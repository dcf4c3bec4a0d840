#pragma once
// Converged backward Euler as a reference (implicit-euler, solve = converged: the line-search
// Newton, docs/integrators/implicit-euler.md): the options the tests' and the benchmarks'
// comparisons share, and one step of it solved to far below the distances the iterative
// methods' tests compare (sparse direct): the step PD, VBD and a converged XPBD approach.
#include <string>

#include "integrators/implicit_euler/implicit_euler.hpp"

namespace drape::testing {

/// implicit-euler's converged step of size dt, stopping at ARKODE's test with weights
/// 1 / (rtol |y_n| + atol), its default linear solver unless `linear_solver` names one, and the
/// line-search Newton's iteration bound; a solve that fails throws instead of halving the step,
/// so that every method compared takes the same step.
inline IntegratorOptions converged_backward_euler(double dt, double rtol, double atol,
                                                  const std::string& linear_solver = "") {
  IntegratorOptions o;
  o.name = "implicit-euler";
  o.dt = dt;
  o.solve = "converged";
  o.linear_solver = linear_solver;
  o.rtol = rtol;
  o.atol = atol;
  o.max_step_halvings = 0;
  return o;
}

inline Eigen::VectorXd backward_euler_step(ClothSystem& s, const Eigen::VectorXd& y0, double dt,
                                           double rtol = 1e-12, double atol = 1e-14) {
  ImplicitEuler method(s, converged_backward_euler(dt, rtol, atol, "sparse-direct"));
  method.reset(0.0, y0);
  method.step(dt);
  return method.state();
}

}  // namespace drape::testing
