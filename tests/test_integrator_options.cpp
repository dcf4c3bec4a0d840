// The defaults that integrator options fall back to.
#include <gtest/gtest.h>

#include "integrators/integrator_options.hpp"

namespace drape {
namespace {

TEST(IntegratorOptions, ImplicitSolvesDefaultToMultigridCg) {
  IntegratorOptions o;
  o.name = "implicit-euler";
  EXPECT_EQ(linear_solver_of(o), "pcg-multigrid");
  EXPECT_EQ(linear_tolerance_of(o), 1e-3);
  o.linear_solver = "pcg-reduced";
  EXPECT_EQ(linear_solver_of(o), "pcg-reduced");
  o.name = "arkode-dirk";
  EXPECT_EQ(linear_tolerance_of(o), 1e-8);
}

}  // namespace
}  // namespace drape
