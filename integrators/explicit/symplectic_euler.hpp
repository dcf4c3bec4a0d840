#pragma once
#include "integrators/interface/integrator.hpp"

namespace drape {

/// Symplectic (semi-implicit) Euler: v(n+1) = v(n) + dt a(x(n), v(n)),
/// x(n+1) = x(n) + dt v(n+1). First order, one force evaluation per step.
class SymplecticEuler final : public Integrator {
 public:
  SymplecticEuler(ClothSystem& system, double dt) : Integrator(system), m_dt(dt) {}
  void reset(double t, const Eigen::VectorXd& y) override;
  double step(double t_stop) override;

 private:
  double m_dt;
  Eigen::VectorXd m_acceleration;
};

}  // namespace drape
