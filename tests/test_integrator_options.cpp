// The defaults that integrator options fall back to.
#include <gtest/gtest.h>

#include "core/input_error.hpp"
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

TEST(IntegratorOptions, StepHalvingsDefaultToTenAndAreBounded) {
  const nlohmann::json dirk = {{"name", "arkode-dirk"}, {"dt", 1e-3}};
  EXPECT_EQ(read_integrator_options(dirk, "scene.json", "integrator").max_step_halvings, 10);
  for (const int bad : {-1, 31}) {
    nlohmann::json o = dirk;
    o["max_step_halvings"] = bad;
    try {
      read_integrator_options(o, "scene.json", "integrator");
      ADD_FAILURE() << bad << " accepted";
    } catch (const InputError& e) {
      EXPECT_STREQ(e.what(), "scene.json: integrator.max_step_halvings: must be between 0 and 30");
    }
  }
}

}  // namespace
}  // namespace drape
