#pragma once
// The exact trajectory of a test system, to far below the errors of the methods under test.
#include <Eigen/Core>

#include "integrators/registry/registry.hpp"
#include "tests/support/test_support.hpp"

namespace drape::testing {

/// The state at t_end from y0 by an order-8 Runge-Kutta (Fehlberg 13(7)8) at step `dt`.
inline Eigen::VectorXd reference_trajectory(ClothSystem& s, const Eigen::VectorXd& y0,
                                            double t_end, double dt = 2.5e-5) {
  IntegratorOptions exact;
  exact.name = "arkode-erk";
  exact.table = "ARKODE_FEHLBERG_13_7_8";
  exact.dt = dt;
  auto method = make_integrator(exact, s);
  method->reset(0.0, y0);
  return run_until(*method, t_end);
}

}  // namespace drape::testing
