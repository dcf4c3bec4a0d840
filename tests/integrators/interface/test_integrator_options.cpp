// The options as an integrator reads them against its own declaration: the value given, or the
// declared default.
#include <gtest/gtest.h>

#include <stdexcept>

#include "integrators/interface/integrator_options.hpp"

namespace drape {
namespace {

TEST(IntegratorOptions, NamedKeysFallBackToTheDeclaredDefaults) {
  const NamedKeys declared = {false, false, true, true, false, "pcg-multigrid", 1e-3};
  IntegratorOptions o;
  EXPECT_EQ(linear_solver_of(o, declared), "pcg-multigrid");
  EXPECT_EQ(linear_tolerance_of(o, declared), 1e-3);
  EXPECT_FALSE(uses_line_search(o, declared));
  EXPECT_EQ(nonlinear_solver_of(o, declared), "");  // no Newton stages declared
  EXPECT_EQ(exact_solve_of(o), "lu");
  o.linear_solver = "sparse-direct";
  o.linear_tolerance = 1e-6;
  o.solve = "converged";
  o.exact_solve = "bicgstab";
  EXPECT_EQ(linear_solver_of(o, declared), "sparse-direct");
  EXPECT_EQ(linear_tolerance_of(o, declared), 1e-6);
  EXPECT_TRUE(uses_line_search(o, declared));
  EXPECT_EQ(exact_solve_of(o), "bicgstab");
}

TEST(IntegratorOptions, NewtonStagesTakeTheLineSearchUnlessNewtonIsNamed) {
  const NamedKeys declared = {true, true, true, false, false};
  IntegratorOptions o;
  EXPECT_EQ(nonlinear_solver_of(o, declared), "line-search");
  EXPECT_TRUE(uses_line_search(o, declared));
  o.nonlinear_solver = "newton";
  EXPECT_FALSE(uses_line_search(o, declared));
}

TEST(IntegratorOptions, NewtonIterationBoundDependsOnTheSolver) {
  IntegratorOptions o;
  EXPECT_EQ(max_newton_iters_of(o, true), 400);
  EXPECT_EQ(max_newton_iters_of(o, false), 10);
  o.max_newton_iters = 7;
  EXPECT_EQ(max_newton_iters_of(o, true), 7);
  EXPECT_EQ(max_newton_iters_of(o, false), 7);
}

TEST(IntegratorOptions, SettingsFallBackToTheDeclarationAndRefuseUndeclaredKeys) {
  const std::vector<SettingKey> declared = {
      SettingKey::integer("iterations", 10, 1, 100, "sweeps"),
      SettingKey::choice("sweep", "jacobi", {"jacobi", "gauss-seidel"}, "order")};
  IntegratorOptions o;
  o.settings = {{"sweep", "gauss-seidel"}};
  EXPECT_EQ(o.setting_integer("iterations", declared), 10);
  EXPECT_EQ(o.setting_choice("sweep", declared), "gauss-seidel");
  EXPECT_THROW(o.setting_number("rho", declared), std::logic_error);
}

}  // namespace
}  // namespace drape
