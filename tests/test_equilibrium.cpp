// A damped pinned cloth settles at the static equilibrium found independently by Newton's method
// on the potential energy.
#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>

#include "integrators/leapfrog.hpp"
#include "integrators/symplectic_euler.hpp"
#include "test_support.hpp"

namespace drape {
namespace {

// Minimises the potential over the free particles: Newton steps on -dF/dx with a backtracking
// line search on the energy; fixed particles stay at their pins.
Eigen::VectorXd newton_equilibrium(const ClothSystem& s) {
  Eigen::VectorXd x = s.initial_state(0.0).head(3 * s.num_particles());
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(x.size());
  const ConstVecMap v(zero.data(), zero.size());
  for (int iter = 0; iter < 100; ++iter) {
    Eigen::VectorXd f = testing::forces_of(s, x, zero);
    s.constraints().zero_fixed(VecMap(f.data(), f.size()));
    if (f.norm() < 1e-13) break;
    Eigen::SparseMatrix<double> dfdx, dfdv;
    // Early iterations use the definite Hessian (always a descent direction), then exact Newton.
    s.force_jacobians(ConstVecMap(x.data(), x.size()), v, iter < 20, dfdx, dfdv);
    Eigen::SparseMatrix<double> hessian = -dfdx;
    for (const int i : s.constraints().fixed_particles())
      for (int a = 0; a < 3; ++a) hessian.coeffRef(3 * i + a, 3 * i + a) = 1.0;
    Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(hessian);
    const Eigen::VectorXd step = lu.solve(f);
    const double e = testing::potential_of(s, x);
    double alpha = 1.0;
    while (testing::potential_of(s, x + alpha * step) > e && alpha > 1e-8) alpha *= 0.5;
    x += alpha * step;
  }
  return x;
}

template <class Method>
Eigen::VectorXd settle(ClothSystem& s, double dt) {
  Method method(s, dt);
  method.reset(0.0, s.initial_state(0.0));
  const Eigen::Index n3 = 3 * s.num_particles();
  while (method.time() < 60.0) {
    method.step(60.0);
    if (method.state().tail(n3).lpNorm<Eigen::Infinity>() < 1e-10) break;
  }
  return method.state().head(n3);
}

TEST(Equilibrium, DampedPinnedClothSettlesOnTheNewtonEquilibrium) {
  auto s = testing::pinned_test_cloth(0.02, 0.002);
  const Eigen::VectorXd expected = newton_equilibrium(*s);
  // The cloth really sags: the equilibrium is far from the rest grid.
  EXPECT_GT((expected - s->cloth().rest_positions).lpNorm<Eigen::Infinity>(), 0.005);
  const Eigen::VectorXd leapfrog = settle<Leapfrog>(*s, 1e-3);
  EXPECT_LT((leapfrog - expected).lpNorm<Eigen::Infinity>(), 1e-8);
  const Eigen::VectorXd euler = settle<SymplecticEuler>(*s, 1e-3);
  EXPECT_LT((euler - expected).lpNorm<Eigen::Infinity>(), 1e-8);
}

}  // namespace
}  // namespace drape
