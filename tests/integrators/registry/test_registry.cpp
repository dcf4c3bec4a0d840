// The integrator list, the ARKODE tables and the validation of table and linear-solver choices.
#include <gtest/gtest.h>

#include "core/io/input_error.hpp"
#include "integrators/registry/registry.hpp"
#include "tests/support/test_support.hpp"

namespace drape {
namespace {

IntegratorOptions options(const std::string& name, const std::string& table = "") {
  IntegratorOptions o;
  o.name = name;
  o.table = table;
  o.dt = 1e-3;
  return o;
}

std::string rejected_field(const IntegratorOptions& o) {
  try {
    validate_integrator_choice(o, "scene.json", "integrator");
  } catch (const InputError& error) {
    EXPECT_EQ(error.file(), "scene.json");
    return error.field();
  }
  return "";
}

TEST(Registry, ListsEveryIntegrator) {
  for (const char* name :
       {"leapfrog", "symplectic-euler", "implicit-euler", "arkode-erk", "arkode-dirk", "arkode-imex"})
    EXPECT_NE(find_integrator(name), nullptr) << name;
  EXPECT_EQ(find_integrator("arkode-dirk")->family, "implicit");
  EXPECT_EQ(find_integrator("arkode-imex")->family, "imex");
  EXPECT_TRUE(find_integrator("arkode-erk")->adaptive);
  EXPECT_FALSE(find_integrator("implicit-euler")->adaptive);
}

TEST(Registry, TablesCarryArkodesOrdersAndStages) {
  const auto tables = integrator_tables();
  auto find = [&](const std::string& name) {
    for (const auto& t : tables)
      if (t.name == name) return t;
    ADD_FAILURE() << name;
    return TableInfo{};
  };
  const TableInfo dp = find("ARKODE_DORMAND_PRINCE_7_4_5");
  EXPECT_EQ(dp.integrator, "arkode-erk");
  EXPECT_EQ(dp.order, 5);
  EXPECT_EQ(dp.embedded_order, 4);
  EXPECT_EQ(dp.stages, 7);
  const TableInfo sdirk = find("ARKODE_SDIRK_2_1_2");
  EXPECT_EQ(sdirk.integrator, "arkode-dirk");
  EXPECT_EQ(sdirk.order, 2);
  const TableInfo pair = find("ARKODE_ARK548L2SAb_8_4_5");
  EXPECT_EQ(pair.integrator, "arkode-imex");
  EXPECT_EQ(pair.order, 5);
  EXPECT_EQ(pair.stages, 8);
  EXPECT_EQ(tables.size(), 15u + 23u + 5u);
}

TEST(Registry, AcceptsTablesOfTheRightKind) {
  EXPECT_EQ(rejected_field(options("arkode-erk", "ARKODE_VERNER_8_5_6")), "");
  EXPECT_EQ(rejected_field(options("arkode-dirk", "ARKODE_KVAERNO_7_4_5")), "");
  EXPECT_EQ(rejected_field(options("arkode-imex", "ARKODE_ARK437L2SA_7_3_4")), "");
  EXPECT_EQ(rejected_field(options("arkode-dirk")), "");
  EXPECT_EQ(rejected_field(options("implicit-euler")), "");
}

TEST(Registry, RejectsBadTablesAndLinearSolvers) {
  EXPECT_EQ(rejected_field(options("arkode-erk", "ARKODE_NO_SUCH_TABLE")), "integrator.table");
  EXPECT_EQ(rejected_field(options("arkode-erk", "ARKODE_SDIRK_2_1_2")), "integrator.table");
  EXPECT_EQ(rejected_field(options("arkode-dirk", "ARKODE_DORMAND_PRINCE_7_4_5")),
            "integrator.table");
  EXPECT_EQ(rejected_field(options("arkode-imex", "ARKODE_ARK324L2SA_DIRK_4_2_3")),
            "integrator.table");
  EXPECT_EQ(rejected_field(options("leapfrog", "ARKODE_DORMAND_PRINCE_7_4_5")),
            "integrator.table");
  IntegratorOptions no_embedding = options("arkode-erk", "ARKODE_KNOTH_WOLKE_3_3");
  EXPECT_EQ(rejected_field(no_embedding), "");
  no_embedding.adaptive = true;
  EXPECT_EQ(rejected_field(no_embedding), "integrator.table");
  IntegratorOptions bad_solver = options("arkode-dirk");
  bad_solver.linear_solver = "dense";
  EXPECT_EQ(rejected_field(bad_solver), "integrator.linear_solver");
  // An explicit integrator solves nothing: a linear solver for it is a mistake in the scene.
  for (const char* name : {"leapfrog", "symplectic-euler", "arkode-erk"}) {
    IntegratorOptions solver_for_explicit = options(name);
    solver_for_explicit.linear_solver = "pcg-reduced";
    EXPECT_EQ(rejected_field(solver_for_explicit), "integrator.linear_solver") << name;
  }
  EXPECT_EQ(rejected_field(options("leapfrog")), "");
}

TEST(Registry, MakesEveryIntegrator) {
  auto s = testing::pinned_test_cloth();
  for (const auto& info : integrators()) {
    auto method = make_integrator(options(info.name), *s);
    method->reset(0.0, s->initial_state(0.0));
    EXPECT_NEAR(method->step(1.0), 1e-3, 1e-15) << info.name;
  }
}

}  // namespace
}  // namespace drape
