#pragma once
// One step of backward Euler solved to far below the distances the iterative methods' tests
// compare (implicit-euler, solve = converged, sparse direct): the step PD, VBD and a converged
// XPBD approach.
#include "integrators/implicit_euler/implicit_euler.hpp"

namespace drape::testing {

inline Eigen::VectorXd backward_euler_step(ClothSystem& s, const Eigen::VectorXd& y0, double dt,
                                           double rtol = 1e-12, double atol = 1e-14) {
  IntegratorOptions o;
  o.name = "implicit-euler";
  o.dt = dt;
  o.solve = "converged";
  o.linear_solver = "sparse-direct";
  o.rtol = rtol;
  o.atol = atol;
  o.max_newton_iters = 200;
  ImplicitEuler method(s, o);
  method.reset(0.0, y0);
  method.step(dt);
  return method.state();
}

}  // namespace drape::testing
