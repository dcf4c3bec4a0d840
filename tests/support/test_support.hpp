#pragma once
// Small systems and finite-difference helpers shared by the tests.
#include <Eigen/Core>
#include <gtest/gtest.h>
#include <Eigen/SparseLU>
#include <functional>
#include <random>

#include "core/dummy/dummy_sources.hpp"
#include "core/model/cloth_system.hpp"
#include "core/io/input_error.hpp"

namespace drape::testing {

/// The message of the InputError that f throws, or "no error".
inline std::string input_error_message(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

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

/// p(t) = start + velocity t: a prescribed motion at a constant velocity.
class LinearTrajectory final : public Trajectory {
 public:
  LinearTrajectory(const Vec3& start, const Vec3& velocity)
      : m_start(start), m_velocity(velocity) {}
  Vec3 position(double t) const override { return m_start + t * m_velocity; }
  Vec3 velocity(double) const override { return m_velocity; }
  Vec3 acceleration(double) const override { return Vec3::Zero(); }

 private:
  Vec3 m_start, m_velocity;
};

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

/// The static equilibrium of a pinned cloth, found independently of any integrator: Newton steps
/// on -dF/dx over the free particles with a backtracking line search on the energy.
inline Eigen::VectorXd newton_equilibrium(const ClothSystem& s) {
  Eigen::VectorXd x = s.initial_state(0.0).head(3 * s.num_particles());
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(x.size());
  const ConstVecMap v(zero.data(), zero.size());
  for (int iter = 0; iter < 100; ++iter) {
    Eigen::VectorXd f = forces_of(s, x, zero);
    s.constraints().zero_fixed(VecMap(f.data(), f.size()));
    if (f.norm() < 1e-13) break;
    Eigen::SparseMatrix<double> dfdx, dfdv;
    // Early iterations use the definite Hessian (always a descent direction), then exact Newton.
    s.force_jacobians(ConstVecMap(x.data(), x.size()), v, iter < 20, dfdx, dfdv);
    // Fixed rows of dF/dx are zero: an identity there keeps their step at zero.
    std::vector<Eigen::Triplet<double>> pinned;
    for (const int i : s.constraints().fixed_particles())
      for (int a = 0; a < 3; ++a) pinned.emplace_back(3 * i + a, 3 * i + a, 1.0);
    Eigen::SparseMatrix<double> identity_on_fixed(x.size(), x.size());
    identity_on_fixed.setFromTriplets(pinned.begin(), pinned.end());
    // A flat cloth at rest has no out-of-plane stiffness (the Hessian is singular there): the
    // first iterations add a small Levenberg-Marquardt shift, the last ones are exact Newton.
    Eigen::SparseMatrix<double> shift(x.size(), x.size());
    shift.setIdentity();
    const double levenberg = iter < 20 ? 1e-3 * s.cloth().params.k_structural : 0.0;
    const Eigen::SparseMatrix<double> hessian = identity_on_fixed - dfdx + levenberg * shift;
    Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(hessian);
    if (lu.info() != Eigen::Success) throw std::runtime_error("newton_equilibrium: singular Hessian");
    const Eigen::VectorXd step = lu.solve(f);
    const double e = potential_of(s, x);
    double alpha = 1.0;
    while (potential_of(s, x + alpha * step) > e && alpha > 1e-8) alpha *= 0.5;
    x += alpha * step;
  }
  return x;
}

}  // namespace drape::testing

#include <memory>

#include "integrators/interface/integrator.hpp"
#include "integrators/explicit/leapfrog.hpp"

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

/// A damped 4 x 5 cloth, one corner pinned, with a sphere just behind its plane: most particles
/// are within the collision threshold (for the split of the forces with contact).
inline std::unique_ptr<ClothSystem> cloth_against_sphere(CollisionModel model,
                                                        double friction = 0.0) {
  ClothParams p = small_cloth(4, 5);
  p.damping_spring = 0.05;
  p.damping_air = 0.01;
  ForceParams forces;
  forces.collision.model = model;
  forces.collision.friction = friction;
  const auto sphere = std::make_shared<const Dummy>(make_dummy(
      nlohmann::json{{"builtin", "sphere"}, {"radius", 0.05}, {"center", {0.04, 0.97, -0.054}}},
      "test", "dummy", "."));
  auto s = std::make_unique<ClothSystem>(build_cloth(p), sphere, forces);
  s->constraints().fix_at(0, s->cloth().rest_positions.segment<3>(0));
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

/// Runs an integrator from the system's initial state until every velocity is below 1e-10
/// (or t = 60 s) and returns the positions: the equilibrium a damped run settles on.
inline Eigen::VectorXd settle(Integrator& method, const ClothSystem& s) {
  method.reset(0.0, s.initial_state(0.0));
  const Eigen::Index n3 = 3 * s.num_particles();
  while (method.time() < 60.0) {
    method.step(60.0);
    if (method.state().tail(n3).lpNorm<Eigen::Infinity>() < 1e-10) break;
  }
  return method.state().head(n3);
}

/// The largest leap-frog step that stays bounded over `duration` from state y0, to 1% by
/// bisection: the stability limit that implicit methods are measured against.
inline double leapfrog_stability_limit(ClothSystem& s, const Eigen::VectorXd& y0,
                                       double duration = 0.5) {
  const Eigen::Index n3 = 3 * s.num_particles();
  auto stable = [&](double dt) {
    Leapfrog method(s, dt);
    method.reset(0.0, y0);
    while (method.time() < duration - 1e-12) {
      method.step(duration);
      // A mode beyond the limit grows by orders of magnitude within a few steps.
      if (!((method.state().head(n3) - y0.head(n3)).lpNorm<Eigen::Infinity>() < 0.5)) return false;
    }
    return true;
  };
  double lo = 1e-5, hi = 0.1;
  while (hi > 1.01 * lo) {
    const double mid = std::sqrt(lo * hi);
    (stable(mid) ? lo : hi) = mid;
  }
  return lo;
}

/// A fixed particle moving on a horizontal circle around `centre`: p(t) = c + r (cos wt, 0, sin wt).
class CircleTrajectory final : public Trajectory {
 public:
  CircleTrajectory(const Vec3& centre, double radius, double omega)
      : m_centre(centre), m_radius(radius), m_omega(omega) {}
  Vec3 position(double t) const override {
    return m_centre + m_radius * Vec3(std::cos(m_omega * t), 0.0, std::sin(m_omega * t));
  }
  Vec3 velocity(double t) const override {
    return m_radius * m_omega * Vec3(-std::sin(m_omega * t), 0.0, std::cos(m_omega * t));
  }
  Vec3 acceleration(double t) const override {
    return -m_radius * m_omega * m_omega * Vec3(std::cos(m_omega * t), 0.0, std::sin(m_omega * t));
  }

 private:
  Vec3 m_centre;
  double m_radius, m_omega;
};

/// pinned_test_cloth (damped) whose corner 3 moves on a circle, and a shaken start state
/// projected onto the constraints: the fixture of the "fixed and moving particles" tests.
struct CirclingCorner {
  std::unique_ptr<ClothSystem> system;
  std::shared_ptr<CircleTrajectory> circle;
  Eigen::VectorXd start;
};

inline CirclingCorner circling_corner() {
  CirclingCorner c{pinned_test_cloth(0.01, 0.001), nullptr, {}};
  c.circle = std::make_shared<CircleTrajectory>(
      c.system->cloth().rest_positions.segment<3>(9) + Vec3(0.0, 0.0, -0.01), 0.01, 20.0);
  c.system->constraints().fix(3, c.circle);
  c.start = shaken_state(*c.system);
  c.system->constraints().project(0.0, VecMap(c.start.data(), 48), VecMap(c.start.data() + 48, 48));
  return c;
}

/// Steps `method` from c.start to t_end; after every step pin 0 is exactly where it started, at
/// rest, and corner 3 exactly on its circle. At the end the corner has dragged its neighbour.
inline void expect_fixed_particles_follow(Integrator& method, const CirclingCorner& c,
                                          double t_end) {
  method.reset(0.0, c.start);
  while (method.time() < t_end - 1e-12) {
    const double t = method.step(t_end);
    const Eigen::VectorXd& state = method.state();
    ASSERT_EQ(state.segment<3>(0), c.start.segment<3>(0));
    ASSERT_TRUE(state.segment<3>(48).isZero());
    ASSERT_EQ(state.segment<3>(9), c.circle->position(t));
    ASSERT_EQ(state.segment<3>(48 + 9), c.circle->velocity(t));
  }
  EXPECT_GT((method.state().segment<3>(6) - c.start.segment<3>(6)).norm(), 1e-3);
}

}  // namespace drape::testing
