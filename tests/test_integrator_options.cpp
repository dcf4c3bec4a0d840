// The defaults that integrator options fall back to.
#include <gtest/gtest.h>

#include "integrators/integrator_options.hpp"

namespace drape {
namespace {

TEST(IntegratorOptions, LinearSolverAndToleranceDefaultPerIntegrator) {
  IntegratorOptions o;
  o.name = "implicit-euler";
  EXPECT_EQ(linear_solver_of(o), "pcg-multigrid");
  EXPECT_EQ(linear_tolerance_of(o), 1e-3);
  o.linear_solver = "pcg-reduced";
  EXPECT_EQ(linear_solver_of(o), "pcg-reduced");
  for (const char* name : {"arkode-dirk", "arkode-imex"}) {
    IntegratorOptions arkode;
    arkode.name = name;
    EXPECT_EQ(linear_solver_of(arkode), "pcg-reduced") << name;
    EXPECT_EQ(linear_tolerance_of(arkode), 1e-8) << name;
    arkode.linear_solver = "pcg-multigrid";
    EXPECT_EQ(linear_solver_of(arkode), "pcg-multigrid") << name;
  }
}

}  // namespace
}  // namespace drape
