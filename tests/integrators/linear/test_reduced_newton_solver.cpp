// The reduced 3N solve of (I - gamma J) z = r against a dense solve of the full 6N system.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>

#include "core/dummy/dummy.hpp"
#include "integrators/linear/reduced_newton_solver.hpp"
#include "tests/support/test_support.hpp"

namespace drape {
namespace {

// I - gamma J with J = [0 I; M^-1 K  M^-1 D] on the free rows and zero fixed rows, from the
// same definite Jacobians the solver uses.
Eigen::MatrixXd dense_newton_matrix(const ClothSystem& s, const Eigen::VectorXd& y, double gamma,
                                    ForceSplit split) {
  const Eigen::Index n3 = 3 * s.num_particles();
  Eigen::SparseMatrix<double> dfdx, dfdv;
  s.force_jacobians(y.head(n3), y.tail(n3), true, dfdx, dfdv, split);
  Eigen::MatrixXd j = Eigen::MatrixXd::Zero(2 * n3, 2 * n3);
  j.block(0, n3, n3, n3).setIdentity();
  for (const int i : s.constraints().fixed_particles()) j.block(3 * i, n3, 3, n3).setZero();
  j.block(n3, 0, n3, n3) = Eigen::MatrixXd(dfdx) / s.particle_mass();
  j.block(n3, n3, n3, n3) = Eigen::MatrixXd(dfdv) / s.particle_mass();
  return Eigen::MatrixXd::Identity(2 * n3, 2 * n3) - gamma * j;
}

TEST(ReducedNewtonSolver, MatchesADenseSolveOfTheFullSystem) {
  for (const ForceSplit split : {ForceSplit::all, ForceSplit::springs, ForceSplit::non_springs,
                                 ForceSplit::springs_and_collision}) {
    for (const ReducedSolve method : {ReducedSolve::conjugate_gradients, ReducedSolve::multigrid_cg,
                                      ReducedSolve::sparse_ldlt}) {
      auto s = testing::pinned_test_cloth(0.05, 0.01);
      const Eigen::Index n3 = 3 * s->num_particles();
      Eigen::VectorXd y = testing::jitter(s->initial_state(0.0), 0.003, 7);
      const double gamma = 0.02;
      const Eigen::VectorXd r = testing::jitter(Eigen::VectorXd::Zero(2 * n3), 1.0, 8);
      ReducedNewtonSolver solver(*s, method, split, 1e-13, 500);
      solver.update(y.head(n3), y.tail(n3), gamma);
      Eigen::VectorXd z(2 * n3);
      ASSERT_TRUE(solver.solve(r, z));
      const Eigen::VectorXd expected =
          dense_newton_matrix(*s, y, gamma, split).partialPivLu().solve(r);
      EXPECT_LT((z - expected).norm(), 1e-10 * expected.norm());
      // A fixed particle's rows are the identity.
      EXPECT_EQ(z.segment<3>(0), r.segment<3>(0));
      EXPECT_EQ(z.segment<3>(n3), r.segment<3>(n3));
    }
  }
}

// The damped pinned cloth at a jittered state (seed) and a random right-hand side (seed + 1).
struct JitteredProblem {
  std::unique_ptr<ClothSystem> s;
  Eigen::Index n3;
  Eigen::VectorXd y, r;
};

JitteredProblem jittered_problem(unsigned seed) {
  auto s = testing::pinned_test_cloth(0.05, 0.01);
  const Eigen::Index n3 = 3 * s->num_particles();
  Eigen::VectorXd y = testing::jitter(s->initial_state(0.0), 0.003, seed);
  Eigen::VectorXd r = testing::jitter(Eigen::VectorXd::Zero(2 * n3), 1.0, seed + 1);
  return {std::move(s), n3, std::move(y), std::move(r)};
}

TEST(ReducedNewtonSolver, NewGammaReusesTheJacobian) {
  auto [s, n3, y, r] = jittered_problem(9);
  ReducedNewtonSolver solver(*s, ReducedSolve::sparse_ldlt, ForceSplit::all, 1e-13, 500);
  EXPECT_FALSE(solver.has_jacobian());
  solver.update(y.head(n3), y.tail(n3), 0.01);
  solver.set_gamma(0.05);
  Eigen::VectorXd z(2 * n3);
  ASSERT_TRUE(solver.solve(r, z));
  const Eigen::VectorXd expected = dense_newton_matrix(*s, y, 0.05, ForceSplit::all).partialPivLu().solve(r);
  EXPECT_LT((z - expected).norm(), 1e-10 * expected.norm());
  solver.invalidate();
  EXPECT_FALSE(solver.has_jacobian());
}

// A rows x cols cloth with the benchmark's stiffness and mass per particle (draped_cloth.hpp),
// its horizontal springs compressed by 15% and the grid crumpled a little, top row pinned: the
// hard start of the implicit-Euler benchmark (which has no bending springs).
std::unique_ptr<ClothSystem> compressed_cloth(int rows, int cols, double k_bending,
                                              Eigen::VectorXd& y) {
  ClothParams p = testing::small_cloth(rows, cols);
  p.spacing = 0.5 / cols;
  p.particle_mass = 0.2 / (rows * cols);
  p.k_structural = p.k_shear = 50.0;
  p.k_bending = k_bending;
  p.damping_spring = 0.01;
  p.damping_air = 0.001;
  auto s = std::make_unique<ClothSystem>(build_cloth(p), nullptr, ForceParams{});
  y = s->initial_state(0.0);
  const Eigen::Index n3 = 3 * s->num_particles();
  for (Eigen::Index i = 0; i < s->num_particles(); ++i) y[3 * i] *= 0.85;
  y.head(n3) = testing::jitter(y.head(n3), 0.05 * p.spacing, 11);
  for (int c = 0; c < cols; ++c) s->constraints().fix_at(c, y.segment<3>(3 * c));
  return s;
}

TEST(ReducedNewtonSolver, MultigridCgMatchesTheFactorisationOnALargerCloth) {
  // Odd, unequal sides (coarse grids of odd and even sizes, the last node of an even side
  // copying its one coarse neighbour) and bending springs (a coupling two particles apart,
  // which widens the coarse patterns).
  Eigen::VectorXd y;
  auto s = compressed_cloth(25, 19, 5.0, y);
  const Eigen::Index n3 = 3 * s->num_particles();
  const Eigen::VectorXd r = testing::jitter(Eigen::VectorXd::Zero(2 * n3), 1.0, 12);
  Eigen::VectorXd z_cg(2 * n3), z_direct(2 * n3);
  ReducedNewtonSolver cg(*s, ReducedSolve::multigrid_cg, ForceSplit::all, 1e-12, 200);
  ReducedNewtonSolver direct(*s, ReducedSolve::sparse_ldlt, ForceSplit::all, 0.0, 1);
  for (ReducedNewtonSolver* solver : {&cg, &direct})
    solver->update(y.head(n3), y.tail(n3), 1.0 / 30.0);
  ASSERT_TRUE(cg.solve(r, z_cg));
  ASSERT_TRUE(direct.solve(r, z_direct));
  EXPECT_LT((z_cg - z_direct).norm(), 1e-9 * z_direct.norm());
}

TEST(ReducedNewtonSolver, MultigridNeedsFarFewerIterationsThanBlockJacobi) {
  Eigen::VectorXd y;
  auto s = compressed_cloth(32, 32, 0.0, y);
  const Eigen::Index n3 = 3 * s->num_particles();
  // Implicit Euler's first right-hand side at 1/30 s, at the default tolerance 1e-3.
  const double h = 1.0 / 30.0;
  Eigen::VectorXd r(2 * n3), z(2 * n3);
  s->rhs(0.0, y, r);
  r *= h;
  s->constraints().zero_fixed(r.head(n3));
  s->constraints().zero_fixed(r.tail(n3));
  long iterations[2];
  for (const ReducedSolve method :
       {ReducedSolve::conjugate_gradients, ReducedSolve::multigrid_cg}) {
    ReducedNewtonSolver solver(*s, method, ForceSplit::all, 1e-3, 1000);
    solver.update(y.head(n3), y.tail(n3), h);
    ASSERT_TRUE(solver.solve(r, z));
    iterations[method == ReducedSolve::multigrid_cg] = solver.iterations();
  }
  EXPECT_LT(4 * iterations[1], iterations[0]) << iterations[1] << " vs " << iterations[0];
}

// The line-search Newton's forcing term (line_search_newton.cpp): a solve's own relative
// residual replaces the constructor's, and 0 keeps the constructor's.
TEST(ReducedNewtonSolver, SolveTolerancesOverrideTheConstructors) {
  auto [s, n3, y, r] = jittered_problem(11);
  ReducedNewtonSolver solver(*s, ReducedSolve::conjugate_gradients, ForceSplit::all, 1e-13, 500);
  solver.update(y.head(n3), y.tail(n3), 1.0 / 30.0);
  Eigen::VectorXd exact(2 * n3), loose(2 * n3);
  ASSERT_TRUE(solver.solve(r, exact, CgStart::zero, 0.0));
  const long tight_iterations = solver.iterations();
  ASSERT_TRUE(solver.solve(r, loose, CgStart::zero, 1e-2));
  const long loose_iterations = solver.iterations() - tight_iterations;
  EXPECT_LT(2 * loose_iterations, tight_iterations);
  EXPECT_GT((loose - exact).norm(), 1e-10 * exact.norm());  // stopped early, not converged
  EXPECT_LT((loose - exact).norm(), 0.1 * exact.norm());
}

// CgStart::projected (Fischer 1998): a right-hand side in the span of the last two gives their
// combination as the start, and CG has nothing left to do.
TEST(ReducedNewtonSolver, ProjectedStartIsExactInTheSpanOfTheLastTwoSolves) {
  auto [s, n3, y, r1] = jittered_problem(13);
  const Eigen::VectorXd r2 = testing::jitter(Eigen::VectorXd::Zero(2 * n3), 1.0, 15);
  ReducedNewtonSolver solver(*s, ReducedSolve::multigrid_cg, ForceSplit::all, 1e-13, 500);
  solver.update(y.head(n3), y.tail(n3), 1.0 / 30.0);
  Eigen::VectorXd z1(2 * n3), z2(2 * n3), z3(2 * n3);
  ASSERT_TRUE(solver.solve(r1, z1, CgStart::projected));
  ASSERT_TRUE(solver.solve(r2, z2, CgStart::projected));
  const long before = solver.iterations();
  ASSERT_GT(before, 0);
  ASSERT_TRUE(solver.solve(2.0 * r1 - 0.5 * r2, z3, CgStart::projected, 1e-10));
  EXPECT_EQ(solver.iterations(), before);
  const Eigen::VectorXd expected = 2.0 * z1 - 0.5 * z2;
  EXPECT_LT((z3 - expected).norm(), 1e-11 * expected.norm());
  // b = 0: the start is 0 and nothing is left to do.
  ASSERT_TRUE(solver.solve(Eigen::VectorXd::Zero(2 * n3), z3, CgStart::projected));
  EXPECT_EQ(solver.iterations(), before);
  EXPECT_EQ(z3, Eigen::VectorXd::Zero(2 * n3));
}

// S = M - gamma D - gamma^2 K on the free particles (M I on a fixed one) and the reduced
// right-hand side b = M r_v + gamma K r_x, dense, for an r that is zero on fixed particles.
void dense_reduced_system(const ClothSystem& s, const Eigen::VectorXd& y, double gamma,
                          const Eigen::VectorXd& r, Eigen::MatrixXd& S, Eigen::VectorXd& b) {
  const Eigen::Index n3 = 3 * s.num_particles();
  Eigen::SparseMatrix<double> dfdx, dfdv;
  s.force_jacobians(y.head(n3), y.tail(n3), true, dfdx, dfdv, ForceSplit::all);
  S = s.particle_mass() * Eigen::MatrixXd::Identity(n3, n3) - gamma * Eigen::MatrixXd(dfdv) -
      gamma * gamma * Eigen::MatrixXd(dfdx);
  b = s.particle_mass() * r.tail(n3) + gamma * (dfdx * r.head(n3));
  for (const int i : s.constraints().fixed_particles()) {
    S.middleRows(3 * i, 3).setZero();
    S.middleCols(3 * i, 3).setZero();
    S.block<3, 3>(3 * i, 3 * i) = s.particle_mass() * Mat3::Identity();
    b.segment<3>(3 * i).setZero();
  }
}

// The start is the Galerkin projection onto the last two solves with the S of this solve (not
// of the solves that made them), and the fixed set of this solve: S changes between the three
// solves (three states) and a particle is fixed before the last. So it minimises the error's
// S-norm over a span that holds 0 and the last solve.
TEST(ReducedNewtonSolver, ProjectedStartIsTheGalerkinProjectionWithTheCurrentS) {
  const double gamma = 1.0 / 30.0;
  auto [s, n3, y, r] = jittered_problem(17);
  ReducedNewtonSolver solver(*s, ReducedSolve::conjugate_gradients, ForceSplit::all, 1e-12, 500);
  Eigen::MatrixXd history(n3, 2);  // column 0 the last solve's z_v
  for (const unsigned seed : {19u, 21u}) {
    const Eigen::VectorXd y_k = testing::jitter(y, 0.01, seed);
    solver.update(y_k.head(n3), y_k.tail(n3), gamma);
    Eigen::VectorXd z(2 * n3);
    ASSERT_TRUE(solver.solve(testing::jitter(r, 0.3, seed + 1), z, CgStart::projected));
    history.col(1) = history.col(0);
    history.col(0) = z.tail(n3);
  }
  s->constraints().fix_at(5, y.segment<3>(15));
  for (const int i : s->constraints().fixed_particles()) {
    r.segment<3>(3 * i).setZero();
    r.segment<3>(n3 + 3 * i).setZero();
  }
  solver.update(y.head(n3), y.tail(n3), gamma);
  Eigen::VectorXd z(2 * n3);
  // A tolerance no residual misses returns the start itself.
  ASSERT_TRUE(solver.solve(r, z, CgStart::projected, 1e300));
  Eigen::MatrixXd S;
  Eigen::VectorXd b;
  dense_reduced_system(*s, y, gamma, r, S, b);
  for (Eigen::Index c = 0; c < 2; ++c) {
    Eigen::VectorXd column = history.col(c);
    s->constraints().zero_fixed(column);
    history.col(c) = column;
  }
  const Eigen::MatrixXd gram = history.transpose() * S * history;
  const Eigen::VectorXd galerkin = history * gram.ldlt().solve(history.transpose() * b);
  EXPECT_LT((z.tail(n3) - galerkin).norm(), 1e-10 * galerkin.norm());
  EXPECT_EQ(z.segment<3>(n3 + 15), Vec3::Zero());
  const Eigen::VectorXd exact = S.ldlt().solve(b);
  const auto error = [&](const Eigen::VectorXd& start) {
    const Eigen::VectorXd e = exact - start;
    return std::sqrt(e.dot(S * e));
  };
  EXPECT_LE(error(galerkin), error(Eigen::VectorXd::Zero(n3)));
  EXPECT_LE(error(galerkin), error(history.col(0)));
}

// The row-wise assembly (each block gathers the springs on it) with two springs on every pair of
// two offsets, one stencil added the other way round (0, -1) and one the same way (1, 1), each
// with its own stiffness and rest length, assembled twice with a particle fixed in between,
// against the dense matrix of the same Jacobians.
TEST(ReducedNewtonSolver, AssemblyAddsSpringsOnOnePairAndFollowsTheFixedSet) {
  for (const ReducedSolve method : {ReducedSolve::conjugate_gradients, ReducedSolve::multigrid_cg,
                                    ReducedSolve::sparse_ldlt}) {
    ClothParams p = testing::small_cloth(4, 4);
    p.damping_spring = 0.05;
    p.damping_air = 0.01;
    Cloth cloth = build_cloth(p);
    cloth.stencils.push_back(
        {0, -1, 3.0 * p.k_structural, 0.7 * p.spacing, SpringFamily::structural});
    cloth.stencils.push_back({1, 1, 3.0 * p.k_shear, 0.9 * p.spacing, SpringFamily::shear});
    cloth.springs = list_springs(cloth.stencils, p.rows, p.cols);
    // An end of the pairs (2, 2)-(2, 3) and (2, 2)-(3, 3), far from the pinned particle 0.
    const int shared = cloth.index(2, 2);
    ClothSystem s(std::move(cloth), nullptr, ForceParams{});
    s.constraints().fix_at(0, s.cloth().rest_positions.segment<3>(0));
    const Eigen::Index n3 = 3 * s.num_particles();
    const Eigen::VectorXd y = testing::jitter(s.initial_state(0.0), 0.003, 23);
    const Eigen::VectorXd r = testing::jitter(Eigen::VectorXd::Zero(2 * n3), 1.0, 24);
    ReducedNewtonSolver solver(s, method, ForceSplit::all, 1e-13, 500);
    for (const int fixed : {-1, shared}) {  // then an end of doubled pairs fixed
      if (fixed >= 0) s.constraints().fix_at(fixed, y.segment<3>(3 * fixed));
      solver.update(y.head(n3), y.tail(n3), 0.02);
      Eigen::VectorXd z(2 * n3);
      ASSERT_TRUE(solver.solve(r, z));
      const Eigen::VectorXd expected =
          dense_newton_matrix(s, y, 0.02, ForceSplit::all).partialPivLu().solve(r);
      EXPECT_LT((z - expected).norm(), 1e-10 * expected.norm()) << static_cast<int>(method);
    }
  }
}

TEST(ReducedNewtonSolver, LinearSolverNames) {
  EXPECT_EQ(reduced_solve_named("pcg-reduced"), ReducedSolve::conjugate_gradients);
  EXPECT_EQ(reduced_solve_named("pcg-multigrid"), ReducedSolve::multigrid_cg);
  EXPECT_EQ(reduced_solve_named("sparse-direct"), ReducedSolve::sparse_ldlt);
  EXPECT_FALSE(reduced_solve_named("klu"));
}

}  // namespace
}  // namespace drape
