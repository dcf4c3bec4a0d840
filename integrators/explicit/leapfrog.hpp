#pragma once
#include "integrators/interface/integrator.hpp"

namespace drape {

/// The paper's leap-frog (section 2.2; docs/model.md section 6): v(n+1/2) = v(n-1/2) + dt a(n),
/// x(n+1) = x(n) + dt v(n+1/2). Run in its kick-drift-kick form, algebraically the same
/// scheme, so that v(n) = v(n+1/2) + dt/2 a(n) is at hand for energy output. Velocity-dependent
/// forces (damping) at step n+1 use v(n+1/2). One force evaluation per step.
class Leapfrog final : public Integrator {
 public:
  Leapfrog(ClothSystem& system, double dt) : Integrator(system), m_dt(dt) {}
  void reset(double t, const Eigen::VectorXd& y) override;
  double step(double t_stop) override;

 private:
  double m_dt;
  Eigen::VectorXd m_acceleration;  // a(n) at the current state, valid while m_have_acceleration
  bool m_have_acceleration = false;
};

}  // namespace drape
