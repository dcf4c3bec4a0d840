// The defaults that integrator options fall back to, and the keys a run would not use.
#include <gtest/gtest.h>

#include "integrators/registry/options_reader.hpp"
#include "integrators/registry/registry.hpp"
#include "tests/support/test_support.hpp"

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

std::string error_of(const nlohmann::json& options) {
  return testing::input_error_message(
      [&] { read_integrator_options(options, "scene.json", "integrator"); });
}

TEST(IntegratorOptions, StepHalvingsDefaultToTenAndAreBounded) {
  const nlohmann::json dirk = {{"name", "arkode-dirk"}, {"dt", 1e-3}};
  EXPECT_EQ(read_integrator_options(dirk, "scene.json", "integrator").max_step_halvings, 10);
  for (const int bad : {-1, 31}) {
    nlohmann::json o = dirk;
    o["max_step_halvings"] = bad;
    EXPECT_EQ(error_of(o), "scene.json: integrator.max_step_halvings: must be between 0 and 30")
        << bad;
  }
}

TEST(IntegratorOptions, MaxStepsIsACheckedInteger) {
  nlohmann::json o = {{"name", "leapfrog"}, {"dt", 1e-3}};
  EXPECT_EQ(read_integrator_options(o, "scene.json", "integrator").max_steps, 100'000'000);
  o["max_steps"] = 1e8;  // the form scenes wrote when it was read as a number
  EXPECT_EQ(read_integrator_options(o, "scene.json", "integrator").max_steps, 100'000'000);
  o["max_steps"] = 0.5;
  EXPECT_EQ(error_of(o), "scene.json: integrator.max_steps: expected an integer, got 0.5");
  o["max_steps"] = 1e300;
  EXPECT_EQ(error_of(o), "scene.json: integrator.max_steps: must be an integer from 1 to "
                         "1000000000000, got 1e+300");
  o["max_steps"] = 0;
  EXPECT_EQ(error_of(o), "scene.json: integrator.max_steps: must be an integer from 1 to "
                         "1000000000000, got 0");
}

TEST(IntegratorOptions, AnEmptyChoiceIsRefusedNotTakenAsTheDefault) {
  // "" came mostly from a failed command substitution, --set integrator.table="$(...)", and ran
  // the default under the name of another.
  for (const auto& [name, key] :
       std::vector<std::pair<std::string, std::string>>{{"arkode-dirk", "table"},
                                                        {"arkode-dirk", "linear_solver"},
                                                        {"arkode-dirk", "nonlinear_solver"},
                                                        {"arkode-imex", "imex_split"},
                                                        {"implicit-euler", "solve"}}) {
    const nlohmann::json o = {{"name", name}, {"dt", 1e-3}, {key, ""}};
    EXPECT_EQ(error_of(o), "scene.json: integrator." + key +
                               ": must not be empty (leave the key out for the default)")
        << key;
  }
}

// A key that the chosen integrator would ignore is an error naming it, like an unknown key.
TEST(IntegratorOptions, KeysTheIntegratorDoesNotReadAreRejected) {
  const struct {
    nlohmann::json options;
    const char* key;
  } unused[] = {
      {{{"name", "leapfrog"}, {"dt", 1e-4}, {"rtol", 1e-3}}, "rtol"},
      {{{"name", "implicit-euler"}, {"dt", 1e-2}, {"atol", 1e-6}}, "atol"},
      {{{"name", "arkode-erk"}, {"dt", 1e-4}, {"max_dt", 1e-3}}, "max_dt"},
      {{{"name", "implicit-euler"}, {"dt", 1e-2}, {"max_newton_iters", 3}}, "max_newton_iters"},
      {{{"name", "arkode-erk"}, {"dt", 1e-4}, {"max_step_halvings", 2}}, "max_step_halvings"},
      {{{"name", "arkode-dirk"}, {"adaptive", true}, {"max_step_halvings", 2}},
       "max_step_halvings"},
      {{{"name", "symplectic-euler"}, {"dt", 1e-4}, {"linear_tolerance", 1e-6}},
       "linear_tolerance"},
      {{{"name", "arkode-erk"}, {"dt", 1e-4}, {"max_linear_iters", 9}}, "max_linear_iters"},
      {{{"name", "arkode-dirk"}, {"dt", 1e-3}, {"imex_split", "springs"}}, "imex_split"},
      {{{"name", "implicit-euler"}, {"dt", 1e-2}, {"exact_solve", "lu"}}, "exact_solve"},
      {{{"name", "arkode-dirk"}, {"dt", 1e-3}, {"nonlinear_solver", "newton"}, {"exact_solve", "lu"}},
       "exact_solve"},
  };
  for (const auto& u : unused) {
    const std::string prefix = "scene.json: integrator." + std::string(u.key) +
                               ": not used by this run of '" +
                               u.options["name"].get<std::string>() + "': only ";
    EXPECT_EQ(error_of(u.options).rfind(prefix, 0), 0u) << error_of(u.options);
  }
  EXPECT_EQ(error_of({{"name", "leapfrog"}, {"dt", 1e-4}, {"rtol", 1e-3}}),
            "scene.json: integrator.rtol: not used by this run of 'leapfrog': only the arkode-* "
            "integrators and, with solve = converged, implicit-euler and bdf2 read it");
}

TEST(IntegratorOptions, KeysAreAcceptedWhereTheyAreRead) {
  const nlohmann::json used[] = {
      {{"name", "arkode-erk"}, {"adaptive", true}, {"rtol", 1e-3}, {"atol", 1e-6}, {"max_dt", 1e-3}},
      {{"name", "arkode-dirk"}, {"dt", 1e-3}, {"max_newton_iters", 4}, {"max_step_halvings", 2},
       {"linear_tolerance", 1e-6}, {"max_linear_iters", 50}},
      {{"name", "arkode-imex"}, {"adaptive", true}, {"max_newton_iters", 4}, {"max_dt", 1e-2}},
      {{"name", "arkode-imex"}, {"dt", 1e-3}, {"imex_split", "springs+collision"}},
      {{"name", "implicit-euler"}, {"dt", 1e-2}, {"linear_tolerance", 1e-4}, {"max_linear_iters", 50}},
  };
  for (const nlohmann::json& options : used)
    EXPECT_EQ(error_of(options), "no error") << options.dump();
}

// linear_solver is read by the integrators that declare linear solves, whatever their family.
TEST(IntegratorOptions, LinearSolverOnlyWhereALinearSystemIsSolved) {
  for (const char* name : {"leapfrog", "arkode-erk", "xpbd", "projective-dynamics", "vbd"})
    EXPECT_EQ(error_of({{"name", name}, {"dt", 1e-3}, {"linear_solver", "pcg-reduced"}}),
              "scene.json: integrator.linear_solver: integrator '" + std::string(name) +
                  "' solves no linear system with CG or LDLT: it takes no linear_solver");
  for (const char* name : {"implicit-euler", "bdf2", "arkode-dirk", "arkode-imex"})
    EXPECT_EQ(error_of({{"name", name}, {"dt", 1e-3}, {"linear_solver", "pcg-reduced"}}),
              "no error")
        << name;
}

// The line search's local phase: a sparse LU (the default) or BiCGSTAB, which needs a
// preconditioner of S.
TEST(IntegratorOptions, ExactSolveIsLuOrBicgstabWithAPreconditioner) {
  const nlohmann::json dirk = {{"name", "arkode-dirk"}, {"dt", 1e-3}};
  EXPECT_EQ(to_json(read_integrator_options(dirk, "f", "integrator")).at("exact_solve"), "lu");
  nlohmann::json o = dirk;
  o["exact_solve"] = "bicgstab";
  EXPECT_EQ(read_integrator_options(o, "f", "integrator").exact_solve, "bicgstab");
  o["exact_solve"] = "gmres";
  EXPECT_EQ(error_of(o), "scene.json: integrator.exact_solve: unknown exact solve 'gmres' (one of: "
                         "lu, bicgstab)");
  o["exact_solve"] = "bicgstab";
  o["linear_solver"] = "sparse-direct";
  EXPECT_EQ(error_of(o).rfind("scene.json: integrator.exact_solve: bicgstab is preconditioned", 0),
            0u)
      << error_of(o);
  EXPECT_EQ(error_of({{"name", "implicit-euler"}, {"dt", 1e-2}, {"solve", "converged"},
                      {"exact_solve", "bicgstab"}}),
            "no error");
  EXPECT_EQ(to_json(read_integrator_options({{"name", "leapfrog"}, {"dt", 1e-4}}, "f", "integrator"))
                .at("exact_solve"),
            "");
}

// Tolerances that control nothing are refused (above 1 no test controls anything).
TEST(IntegratorOptions, TolerancesAreBoundedAbove) {
  const nlohmann::json adaptive = {{"name", "arkode-erk"}, {"adaptive", true}};
  nlohmann::json o = adaptive;
  o["rtol"] = 1e300;
  EXPECT_EQ(error_of(o), "scene.json: integrator.rtol: must be at most 1.0, got 1e+300");
  o = adaptive;
  o["atol"] = 2.0;
  EXPECT_EQ(error_of(o), "scene.json: integrator.atol: must be at most 1.0, got 2.0");
  EXPECT_EQ(error_of({{"name", "implicit-euler"}, {"dt", 0.01}, {"linear_tolerance", 1.0}}),
            "scene.json: integrator.linear_tolerance: must be below 1 (a relative residual of 1 "
            "is met by the zero start: nothing would be solved)");
  EXPECT_EQ(error_of({{"name", "implicit-euler"}, {"dt", 0.01}, {"linear_tolerance", 0.5}}),
            "no error");
}

// arkode-imex's split names the forces on the implicit side: two choices, anything else named.
TEST(IntegratorOptions, ImexSplitIsOneOfTwo) {
  EXPECT_EQ(error_of({{"name", "arkode-imex"}, {"dt", 1e-3}, {"imex_split", "collision"}}),
            "scene.json: integrator.imex_split: unknown split 'collision' (one of: springs, "
            "springs+collision)");
  for (const char* split : {"springs", "springs+collision"})
    EXPECT_EQ(error_of({{"name", "arkode-imex"}, {"dt", 1e-3}, {"imex_split", split}}), "no error");
}

}  // namespace
}  // namespace drape
