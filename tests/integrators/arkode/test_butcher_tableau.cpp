// Inline Butcher tables of arkode-dirk: consistency checks naming the field, and the orders of
// backward Euler (1), the implicit midpoint rule (2) and Alexander's SDIRK2 (2) given as user tables.
#include <gtest/gtest.h>

#include <cmath>

#include "integrators/arkode/butcher_tableau.hpp"
#include "integrators/registry/options_reader.hpp"
#include "integrators/registry/registry.hpp"
#include "tests/support/test_support.hpp"

namespace drape {
namespace {

const nlohmann::json backward_euler = {{"c", {1.0}}, {"A", {{1.0}}}, {"b", {1.0}}};
const nlohmann::json implicit_midpoint = {{"c", {0.5}}, {"A", {{0.5}}}, {"b", {1.0}}};
// Alexander's SDIRK2 (1977), gamma = 1 - 1/sqrt(2): the benchmarks' alexander-sdirk2.
const double alexander_gamma = 1.0 - 1.0 / std::sqrt(2.0);
const nlohmann::json alexander_sdirk2 = {
    {"c", {alexander_gamma, 1.0}},
    {"A", {{alexander_gamma, 0.0}, {1.0 - alexander_gamma, alexander_gamma}}},
    {"b", {1.0 - alexander_gamma, alexander_gamma}}};

std::string error_of(const nlohmann::json& table) {
  return testing::input_error_message([&] { read_butcher_tableau(table, "scene.json", "integrator.table"); });
}

TEST(ButcherTableau, ReadsOrdersFromTheConditions) {
  EXPECT_EQ(read_butcher_tableau(backward_euler, "f", "t").q, 1);
  EXPECT_EQ(read_butcher_tableau(implicit_midpoint, "f", "t").q, 2);
  // Alexander's SDIRK2 with backward Euler's weights as embedding.
  nlohmann::json embedded = alexander_sdirk2;
  embedded["d"] = {0.0, 1.0};
  const ButcherTableau t = read_butcher_tableau(embedded, "f", "t");
  EXPECT_EQ(t.q, 2);
  EXPECT_EQ(t.p, 1);
}

TEST(ButcherTableau, InconsistentTablesNameTheirField) {
  nlohmann::json t = implicit_midpoint;
  t["b"] = {0.9};
  EXPECT_NE(error_of(t).find("integrator.table.b"), std::string::npos) << error_of(t);
  t = implicit_midpoint;
  t["c"] = {0.4};
  EXPECT_NE(error_of(t).find("integrator.table.c"), std::string::npos) << error_of(t);
  t = {{"c", {0.5, 1.0}}, {"A", {{0.5, 0.5}, {0.5, 0.5}}}, {"b", {0.5, 0.5}}};
  EXPECT_NE(error_of(t).find("lower triangular"), std::string::npos) << error_of(t);
  t = {{"c", {0.5, 1.0}}, {"A", {{0.5}, {0.5, 0.5}}}, {"b", {0.5, 0.5}}};
  EXPECT_NE(error_of(t).find("integrator.table.A"), std::string::npos) << error_of(t);
  t = implicit_midpoint;
  t["b"] = {1.0, 0.0};
  EXPECT_NE(error_of(t).find("integrator.table.b"), std::string::npos) << error_of(t);
  t = backward_euler;
  t["q"] = 2;
  EXPECT_NE(error_of(t).find("integrator.table.q"), std::string::npos) << error_of(t);
  t = backward_euler;
  t["p"] = 1;
  EXPECT_NE(error_of(t).find("integrator.table.p"), std::string::npos) << error_of(t);
  // No implicit stage: ARKODE refused it only when the run started.
  t = {{"c", {0.0, 0.0}}, {"A", {{0.0, 0.0}, {0.0, 0.0}}}, {"b", {0.5, 0.5}}};
  const std::string explicit_method =
      "scene.json: integrator.table.A: has no diagonal entry beyond 1e-12 in magnitude: that is an "
      "explicit method to ARKODE, and arkode-dirk needs at least one implicit stage";
  EXPECT_EQ(error_of(t), explicit_method);
  // Nor does a diagonal at or below 1e-12, which ARKODE counts as explicit (ARK_ILL_INPUT).
  t = {{"c", {1e-300}}, {"A", {{1e-300}}}, {"b", {1.0}}};
  EXPECT_EQ(error_of(t), explicit_method);
  t = {{"c", {1e-12}}, {"A", {{1e-12}}}, {"b", {1.0}}};
  EXPECT_EQ(error_of(t), explicit_method);
  // Stages are bounded: 65 is refused before A is read.
  t = {{"c", std::vector<double>(65, 1.0)}, {"A", nlohmann::json::array()}, {"b", {1.0}}};
  EXPECT_EQ(error_of(t), "scene.json: integrator.table.c: has 65 nodes, more than the limit of 64 stages");
  // An explicit first stage (ESDIRK) is diagonally implicit.
  t = {{"c", {0.0, 1.0}}, {"A", {{0.0, 0.0}, {0.5, 0.5}}}, {"b", {0.5, 0.5}}};
  EXPECT_EQ(error_of(t), "no error");
  // Coefficients are bounded before any sum is formed.
  t = {{"c", {1e300, -1e300}}, {"A", {{1e300, 0.0}, {-2e300, 1e300}}}, {"b", {0.5, 0.5}}};
  EXPECT_EQ(error_of(t), "scene.json: integrator.table.c: must be within +-1000.0");
  t = implicit_midpoint;
  t["A"] = {{1e300}};
  EXPECT_EQ(error_of(t), "scene.json: integrator.table.A: must be within +-1000.0");
  t = implicit_midpoint;
  t["d"] = {-1e300};
  EXPECT_EQ(error_of(t), "scene.json: integrator.table.d: must be within +-1000.0");
  // An embedding equal to b estimates an error of zero.
  t = implicit_midpoint;
  t["d"] = {1.0};
  EXPECT_EQ(error_of(t), "scene.json: integrator.table.d: equals b: an embedding must differ from "
                         "b to estimate the error");
  // The consistency tolerance, 1e-10: a published table's last digits pass, a wrong digit not.
  t = implicit_midpoint;
  t["c"] = {0.5 + 5e-11};
  EXPECT_EQ(error_of(t), "no error");
  t["c"] = {0.5 + 2e-10};
  EXPECT_NE(error_of(t).find("integrator.table.c"), std::string::npos) << error_of(t);
}

TEST(ButcherTableau, OnlyArkodeDirkTakesAnInlineTable) {
  const nlohmann::json scene = {{"name", "arkode-erk"}, {"dt", 0.01}, {"table", backward_euler}};
  EXPECT_NE(testing::input_error_message([&] { read_integrator_options(scene, "f", "integrator"); })
                .find("integrator.table"),
            std::string::npos);
  nlohmann::json adaptive = {{"name", "arkode-dirk"}, {"adaptive", true}, {"table", backward_euler}};
  EXPECT_NE(testing::input_error_message([&] { read_integrator_options(adaptive, "f", "integrator"); })
                .find("integrator.table.d"),
            std::string::npos);
  const IntegratorOptions o = read_integrator_options(
      {{"name", "arkode-dirk"}, {"dt", 0.01}, {"table", implicit_midpoint}}, "f", "integrator");
  EXPECT_EQ(to_json(o).at("table"), implicit_midpoint);
}

struct UserTableCase {
  const char* name;
  int order;
  double t_end, dt0;
};

class UserTableOrder : public ::testing::TestWithParam<UserTableCase> {};

TEST_P(UserTableOrder, FixedStepErrorHasTheTableOrder) {
  const auto [name, order, t_end, dt0] = GetParam();
  const std::string table_name = name;
  const nlohmann::json table = table_name == "backward_euler"      ? backward_euler
                               : table_name == "implicit_midpoint" ? implicit_midpoint
                                                                   : alexander_sdirk2;
  auto s = testing::pinned_test_cloth();
  const Eigen::VectorXd y0 = testing::shaken_state(*s);
  IntegratorOptions exact;
  exact.name = "arkode-erk";
  exact.table = "ARKODE_FEHLBERG_13_7_8";
  exact.dt = 2.5e-5;
  auto reference_method = make_integrator(exact, *s);
  reference_method->reset(0.0, y0);
  const Eigen::VectorXd reference = testing::run_until(*reference_method, t_end);
  std::vector<double> dts, errors;
  for (int k = 0; k < 4; ++k) {
    dts.push_back(dt0 / (1 << k));
    const IntegratorOptions o = read_integrator_options(
        {{"name", "arkode-dirk"}, {"dt", dts.back()}, {"table", table}, {"nonlinear_solver", "line-search"}, {"rtol", 1e-12},
         {"atol", 1e-14}},
        "test", "integrator");
    auto method = make_integrator(o, *s);
    method->reset(0.0, y0);
    const Eigen::VectorXd y = testing::run_until(*method, t_end);
    errors.push_back((y - reference).head(y.size() / 2).norm());
  }
  EXPECT_NEAR(testing::fitted_order(dts, errors), order, 0.3) << name;
}

INSTANTIATE_TEST_SUITE_P(Tables, UserTableOrder,
                         // Backward Euler damps a mode of frequency w by about h w^2 t / 2: on the
                         // shaken cloth (w up to about 450 rad/s) that is 5 at dt = 1e-3 over
                         // 0.05 s, and the error of the damped fast modes, not h, set the measured
                         // slope (0.67). Its asymptotic range needs h w^2 t << 1: 0.005 s from 1e-4.
                         ::testing::Values(UserTableCase{"backward_euler", 1, 0.005, 1e-4},
                                           UserTableCase{"implicit_midpoint", 2, 0.05, 1e-3},
                                           UserTableCase{"alexander_sdirk2", 2, 0.05, 1e-3}),
                         [](const auto& test) { return std::string(test.param.name); });

}  // namespace
}  // namespace drape
