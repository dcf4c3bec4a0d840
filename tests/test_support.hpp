#pragma once
// Small systems and finite-difference helpers shared by the tests.
#include <Eigen/Core>
#include <functional>
#include <random>

#include "core/cloth_system.hpp"

namespace drape::testing {

/// A hanging rows x cols cloth with no object, springs of every family, 2 cm spacing.
inline ClothParams small_cloth(int rows, int cols) {
  ClothParams p;
  p.rows = rows;
  p.cols = cols;
  p.spacing = 0.02;
  p.origin = Vec3(0.0, 1.0, 0.0);
  p.particle_mass = 0.001;
  p.k_structural = 20.0;
  p.k_shear = 10.0;
  p.k_bending = 2.0;
  return p;
}

/// Central finite-difference derivative of a scalar function of a vector.
inline Eigen::VectorXd fd_gradient(const std::function<double(const Eigen::VectorXd&)>& f,
                                   Eigen::VectorXd x, double h) {
  Eigen::VectorXd g(x.size());
  for (Eigen::Index k = 0; k < x.size(); ++k) {
    const double x0 = x[k];
    x[k] = x0 + h;
    const double fp = f(x);
    x[k] = x0 - h;
    const double fm = f(x);
    x[k] = x0;
    g[k] = (fp - fm) / (2 * h);
  }
  return g;
}

/// Uniform random perturbation of every entry by at most `amplitude`.
inline Eigen::VectorXd jitter(const Eigen::VectorXd& x, double amplitude, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-amplitude, amplitude);
  Eigen::VectorXd out = x;
  for (Eigen::Index k = 0; k < out.size(); ++k) out[k] += u(rng);
  return out;
}

/// Forces of a system at positions x and velocities v (convenience for tests).
inline Eigen::VectorXd forces_of(const ClothSystem& s, const Eigen::VectorXd& x,
                                 const Eigen::VectorXd& v) {
  Eigen::VectorXd f(x.size());
  s.forces(ConstVecMap(x.data(), x.size()), ConstVecMap(v.data(), v.size()),
           VecMap(f.data(), f.size()));
  return f;
}

/// Potential energy (spring + gravity + collision) of a system at positions x.
inline double potential_of(const ClothSystem& s, const Eigen::VectorXd& x) {
  const Eigen::VectorXd v = Eigen::VectorXd::Zero(x.size());
  const EnergyBreakdown e =
      s.energy(ConstVecMap(x.data(), x.size()), ConstVecMap(v.data(), v.size()));
  return e.spring + e.gravity + e.collision;
}

}  // namespace drape::testing

#include <memory>

#include "integrators/integrator.hpp"

namespace drape::testing {

/// Least-squares slope of log(error) against log(dt): the observed order of accuracy.
inline double fitted_order(const std::vector<double>& dts, const std::vector<double>& errors) {
  const auto n = static_cast<double>(dts.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t k = 0; k < dts.size(); ++k) {
    const double lx = std::log(dts[k]), ly = std::log(errors[k]);
    sx += lx;
    sy += ly;
    sxx += lx * lx;
    sxy += lx * ly;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

/// Steps an integrator from its current state to t_end and returns the final state.
inline Eigen::VectorXd run_until(Integrator& integrator, double t_end) {
  while (integrator.time() < t_end - 1e-12) integrator.step(t_end);
  return integrator.state();
}

/// An undamped 4 x 4 cloth with no object, its top corners pinned, released from a shaken
/// grid: smooth, nonlinear motion for order-of-accuracy tests.
inline std::unique_ptr<ClothSystem> pinned_test_cloth(double damping_spring = 0.0,
                                                      double damping_air = 0.0) {
  ClothParams p = small_cloth(4, 4);
  p.damping_spring = damping_spring;
  p.damping_air = damping_air;
  auto s = std::make_unique<ClothSystem>(build_cloth(p), nullptr, ForceParams{});
  s->constraints().fix_at(0, s->cloth().rest_positions.segment<3>(0));
  s->constraints().fix_at(3, s->cloth().rest_positions.segment<3>(9));
  return s;
}

/// A start state of pinned_test_cloth with the free particles displaced a little.
inline Eigen::VectorXd shaken_state(const ClothSystem& s) {
  Eigen::VectorXd y = s.initial_state(0.0);
  const Eigen::Index n3 = 3 * s.num_particles();
  y.head(n3) = jitter(y.head(n3), 0.002, 42);
  s.constraints().project(0.0, VecMap(y.data(), n3), VecMap(y.data() + n3, n3));
  return y;
}

}  // namespace drape::testing
