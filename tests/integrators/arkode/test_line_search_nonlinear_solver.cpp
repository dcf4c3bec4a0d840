// ARKODE's implicit stages solved by the line-search Newton: the tables keep their
// orders, and the swinging sheet runs at 1/30 s with no failure and no halving, at the shipped
// stiffness and at 100x.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "integrators/arkode/arkode_stepper.hpp"
#include "integrators/registry/options_reader.hpp"
#include "integrators/registry/registry.hpp"
#include "tests/support/swinging_sheet.hpp"

namespace drape {
namespace {

IntegratorOptions line_search_options(const std::string& name, const std::string& table,
                                      double dt) {
  IntegratorOptions o;
  o.name = name;
  o.table = table;
  o.dt = dt;
  if (name != "arkode-erk") o.nonlinear_solver = "line-search";
  validate_integrator_choice(o, "test", "integrator");
  return o;
}

Eigen::VectorXd run(ClothSystem& s, const IntegratorOptions& o, const Eigen::VectorXd& y0,
                    double t_end, IntegratorCounters* counters = nullptr) {
  auto method = make_integrator(o, s);
  method->reset(0.0, y0);
  const Eigen::VectorXd y = testing::run_until(*method, t_end);
  if (counters) *counters = method->counters();
  return y;
}

struct OrderCase {
  const char* table;
  int order;
  double dt0;
};

class LineSearchOrder : public ::testing::TestWithParam<OrderCase> {};

TEST_P(LineSearchOrder, FixedStepErrorKeepsTheTableOrder) {
  const OrderCase c = GetParam();
  auto s = testing::pinned_test_cloth();
  const Eigen::VectorXd y0 = testing::shaken_state(*s);
  const double t_end = 0.05;
  IntegratorOptions reference_options = line_search_options("arkode-erk", "ARKODE_FEHLBERG_13_7_8", 2.5e-5);
  const Eigen::VectorXd reference = run(*s, reference_options, y0, t_end);
  std::vector<double> dts, errors;
  for (int k = 0; k < 4; ++k) {
    dts.push_back(c.dt0 / (1 << k));
    IntegratorOptions o = line_search_options("arkode-dirk", c.table, dts.back());
    // Newton's test far below the truncation errors measured.
    o.rtol = 1e-12;
    o.atol = 1e-14;
    const Eigen::VectorXd y = run(*s, o, y0, t_end);
    errors.push_back((y - reference).head(y.size() / 2).norm());
  }
  EXPECT_NEAR(testing::fitted_order(dts, errors), c.order, 0.3) << c.table;
}

INSTANTIATE_TEST_SUITE_P(Tables, LineSearchOrder,
                         ::testing::Values(OrderCase{"ARKODE_SDIRK_2_1_2", 2, 1e-3},
                                           OrderCase{"ARKODE_ARK324L2SA_DIRK_4_2_3", 3, 1e-3},
                                           OrderCase{"ARKODE_ESDIRK437L2SA_7_3_4", 4, 1e-3}),
                         [](const auto& test) { return std::string(test.param.table).substr(7); });

struct SheetCase {
  const char* integrator;
  const char* table;
};

// The tables that run the sheet at 1/30 s with no failure (docs/integrators/line-search-newton.md,
// "Measured on the swinging sheet"). ESDIRK437L2SA_7_3_4 gains energy at this step with its stages
// solved (stable at 1/120 s), and so, measured, do SDIRK_5_3_4, ARK548L2SA_DIRK_8_4_5,
// ARK437L2SA_DIRK_7_3_4, QESDIRK436L2SA_6_3_4 and the two ESDIRK547 tables: no stage solver
// can make them pass.
std::vector<SheetCase> implicit_tables() {
  std::vector<SheetCase> cases;
  for (const char* table :
       {"SDIRK_2_1_2", "BILLINGTON_3_3_2", "TRBDF2_3_3_2", "KVAERNO_4_2_3", "ARK324L2SA_DIRK_4_2_3",
        "CASH_5_2_4", "CASH_5_3_4", "KVAERNO_5_3_4", "ARK436L2SA_DIRK_6_3_4", "KVAERNO_7_4_5",
        "ARK548L2SAb_DIRK_8_4_5", "ESDIRK324L2SA_4_2_3", "ESDIRK325L2SA_5_2_3",
        "ESDIRK32I5L2SA_5_2_3", "ESDIRK436L2SA_6_3_4", "ESDIRK43I6L2SA_6_3_4"})
    cases.push_back({"arkode-dirk", table});
  // IMEX pairs (the springs implicit): ARK437L2SA_7_3_4 and ARK548L2SA_8_4_5 gain energy.
  // ARK324L2SA_4_2_3 halved one step in the measurement of docs/integrators/line-search-newton.md
  // (a stage sliding along a saddle of the potential), made before the Levenberg-Marquardt shift;
  // it passes since (at the bounds of 100 and 400 alike).
  for (const char* pair : {"ARK324L2SA_4_2_3", "ARK436L2SA_6_3_4", "ARK548L2SAb_8_4_5"})
    cases.push_back({"arkode-imex", pair});
  return cases;
}

// The measurement: fixed-step ARKODE Newton had 62-288 convergence failures a run here
// and halved steps at 100x stiffness.
void expect_sheet_runs(double stiffness_factor, const std::vector<SheetCase>& cases) {
  for (const SheetCase& c : cases) {
    auto s = testing::swinging_sheet(stiffness_factor);
    IntegratorCounters counters;
    const auto start = std::chrono::steady_clock::now();
    const Eigen::VectorXd y =
        run(*s, line_search_options(c.integrator, std::string("ARKODE_") + c.table, 1.0 / 30.0),
            s->initial_state(0.0), 1.0, &counters);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_EQ(counters.convergence_failures, 0) << c.table << " at " << stiffness_factor << "x";
    EXPECT_EQ(counters.step_halvings, 0) << c.table << " at " << stiffness_factor << "x";
    EXPECT_EQ(counters.steps, 30) << c.table;
    EXPECT_TRUE(y.allFinite()) << c.table;
    std::cout << c.table << " " << stiffness_factor << "x: " << counters.newton_iters
              << " Newton iterations, " << counters.line_search_backtracks << " backtracks, "
              << seconds << " s\n";
  }
}

TEST(LineSearchNonlinearSolver, SwingingSheetAtOneThirtiethSecond) {
  expect_sheet_runs(1.0, implicit_tables());
}

// At 100x stiffness, every table and pair of the shipped stiffness's list except the two that
// gain energy at 100x only (BILLINGTON_3_3_2 and KVAERNO_7_4_5,
// docs/findings/energy_gaining_tables.md, "Which tables gain energy at large steps"); the stages
// take 2-5 times the iterations of the shipped stiffness. ARK436L2SA_DIRK and ESDIRK32I5L2SA halved
// one step each in the measurement of docs/integrators/line-search-newton.md, made before the
// Levenberg-Marquardt shift; they pass since (at the bounds of 100 and 400 alike).
TEST(LineSearchNonlinearSolver, StiffSwingingSheetAtOneThirtiethSecond) {
  std::vector<SheetCase> cases = implicit_tables();
  cases.erase(std::remove_if(cases.begin(), cases.end(),
                             [](const SheetCase& c) {
                               return std::string(c.table) == "BILLINGTON_3_3_2" ||
                                      std::string(c.table) == "KVAERNO_7_4_5";
                             }),
              cases.end());
  expect_sheet_runs(100.0, cases);
}

// Long damped runs settle where the sheet's forces balance: zero velocity and zero force on
// every free particle (the static equilibrium; 60 s of 1/30 s steps, about 40 s here).
TEST(LineSearchNonlinearSolver, SwingingSheetSettlesOnTheStaticEquilibrium) {
  for (const double stiffness_factor : {1.0, 100.0}) {
    auto s = testing::swinging_sheet(stiffness_factor);
    const Eigen::VectorXd y = run(*s, line_search_options("arkode-dirk", "ARKODE_SDIRK_2_1_2",
                                                          1.0 / 30.0),
                                  s->initial_state(0.0), 60.0);
    const Eigen::Index n3 = y.size() / 2;
    Eigen::VectorXd f(n3);
    s->forces(y.head(n3), Eigen::VectorXd::Zero(n3), f);
    s->constraints().zero_fixed(f);
    const double weight = s->particle_mass() * 9.81;
    EXPECT_LT(f.lpNorm<Eigen::Infinity>(), 1e-6 * weight) << stiffness_factor << "x";
    EXPECT_LT(y.tail(n3).lpNorm<Eigen::Infinity>(), 1e-6) << stiffness_factor << "x";
  }
}

// Not a test: the measurement behind docs/integrators/line-search-newton.md's table ("Measured on
// the swinging sheet"), every DIRK table and IMEX pair at both stiffnesses, 1 s at 1/30 s. Run it
// with --gtest_also_run_disabled_tests --gtest_filter='*DISABLED_MeasureEveryTable'.
TEST(LineSearchNonlinearSolver, DISABLED_MeasureEveryTable) {
  for (const double stiffness_factor : {1.0, 100.0}) {
    for (const ArkodeTable& table : arkode_tables()) {
      if (table.kind == ArkodeKind::explicit_rk) continue;
      auto s = testing::swinging_sheet(stiffness_factor);
      const char* name = table.kind == ArkodeKind::imex ? "arkode-imex" : "arkode-dirk";
      auto method = make_integrator(line_search_options(name, table.name, 1.0 / 30.0), *s);
      method->reset(0.0, s->initial_state(0.0));
      std::string outcome = "ran";
      try {
        testing::run_until(*method, 1.0);
      } catch (const IntegratorFailure& failure) {
        outcome = failure.what();
      }
      const Eigen::VectorXd& y = method->state();
      const Eigen::Index n3 = y.size() / 2;
      const IntegratorCounters& c = method->counters();
      std::cout << table.name << " " << stiffness_factor << "x: " << c.convergence_failures
                << " failures, " << c.step_halvings << " halvings, " << c.newton_iters
                << " Newton iterations, " << c.line_search_backtracks << " backtracks, energy "
                << s->energy(y.head(n3), y.tail(n3)).total() << " J, " << outcome << "\n";
    }
  }
}

// The local phase by BiCGSTAB (exact_solve = bicgstab), with Alexander's SDIRK2 and with
// SDIRK_2_1_2 on the sheet at 1/30 s: 1 s at the shipped stiffness and at 100x with no failure
// and no halving, BiCGSTAB's iterations counted as linear iterations; and one step with the
// stages solved to rtol 1e-10 lands where the LU's lands. (Over 1 s at the default tolerance
// the two end 2-3 mm apart: the buckling sheet amplifies the stages' admitted error, 0.1 in
// ARKODE's weighted norm, about 1e-4 m a component; a chaotic run is one sample.)
TEST(LineSearchNonlinearSolver, BicgstabExactDirectionsRunTheSheetLikeTheLu) {
  const double g = 1.0 - 1.0 / std::sqrt(2.0);
  const nlohmann::json alexander = {
      {"c", {g, 1.0}}, {"A", {{g, 0.0}, {1.0 - g, g}}}, {"b", {1.0 - g, g}}};
  const auto options = [](const nlohmann::json& table, const char* exact_solve, double rtol) {
    return read_integrator_options({{"name", "arkode-dirk"}, {"dt", 1.0 / 30.0}, {"table", table},
                                    {"linear_solver", "pcg-multigrid"}, {"rtol", rtol},
                                    {"atol", 1e-3 * rtol}, {"exact_solve", exact_solve}},
                                   "test", "integrator");
  };
  for (const nlohmann::json& table : {alexander, nlohmann::json("ARKODE_SDIRK_2_1_2")}) {
    for (const double stiffness_factor : {1.0, 100.0}) {
      IntegratorCounters lu, bicgstab;
      auto s = testing::swinging_sheet(stiffness_factor);
      run(*s, options(table, "lu", 1e-4), s->initial_state(0.0), 1.0, &lu);
      run(*s, options(table, "bicgstab", 1e-4), s->initial_state(0.0), 1.0, &bicgstab);
      EXPECT_EQ(bicgstab.convergence_failures, 0) << table << " " << stiffness_factor << "x";
      EXPECT_EQ(bicgstab.step_halvings, 0) << table << " " << stiffness_factor << "x";
      EXPECT_EQ(bicgstab.steps, 30) << table;
      EXPECT_GT(bicgstab.linear_iters, lu.linear_iters) << table;
    }
    auto s = testing::swinging_sheet(1.0);
    const Eigen::VectorXd y_lu =
        run(*s, options(table, "lu", 1e-10), s->initial_state(0.0), 1.0 / 30.0);
    const Eigen::VectorXd y_bicgstab =
        run(*s, options(table, "bicgstab", 1e-10), s->initial_state(0.0), 1.0 / 30.0);
    // Each stage's admitted error, 0.1 in the weighted RMS norm of 6N components, is at most
    // 0.1 sqrt(6N) (1e-10 |y| + 1e-13), about 4e-10 m here.
    EXPECT_LT((y_bicgstab - y_lu).lpNorm<Eigen::Infinity>(), 1e-8) << table;
  }
}

TEST(LineSearchNonlinearSolver, CountsBacktracksAndSkipsArkodesLinearSolver) {
  auto s = testing::swinging_sheet(100.0);
  IntegratorCounters c;
  run(*s, line_search_options("arkode-dirk", "ARKODE_SDIRK_2_1_2", 1.0 / 30.0),
      s->initial_state(0.0), 0.2, &c);
  EXPECT_GT(c.line_search_backtracks, 0);
  EXPECT_GT(c.linear_iters, 0);  // the CG iterations of the Hessian solves
  EXPECT_GT(c.jacobian_setups, 0);
  EXPECT_EQ(c.to_json().at("line_search_backtracks"), c.line_search_backtracks);
}

// The line search is the default stage solver of arkode-dirk and arkode-imex, with a
// bound of 400 iterations a stage; `newton` keeps ARKODE's, with its bound of 10.
TEST(LineSearchNonlinearSolver, IsTheDefaultOfTheNewtonIntegrators) {
  for (const char* name : {"arkode-dirk", "arkode-imex"}) {
    IntegratorOptions o;
    o.name = name;
    o.dt = 1.0 / 30.0;
    EXPECT_TRUE(uses_line_search(o)) << name;
    EXPECT_EQ(max_newton_iters_of(o), 400) << name;
    EXPECT_EQ(to_json(o).at("nonlinear_solver"), "line-search") << name;
    o.nonlinear_solver = "newton";
    EXPECT_FALSE(uses_line_search(o)) << name;
    EXPECT_EQ(max_newton_iters_of(o), 10) << name;
    EXPECT_EQ(to_json(o).at("nonlinear_solver"), "newton") << name;
  }
  // A run with nothing said takes the line search's steps: it backtracks, and it takes the
  // stiff sheet's 1/30 s steps without a halving, as the explicit choice does.
  auto s = testing::swinging_sheet(100.0);
  IntegratorOptions o;
  o.name = "arkode-dirk";
  o.table = "ARKODE_SDIRK_2_1_2";
  o.dt = 1.0 / 30.0;
  validate_integrator_choice(o, "test", "integrator");
  IntegratorCounters c;
  run(*s, o, s->initial_state(0.0), 0.2, &c);
  EXPECT_GT(c.line_search_backtracks, 0);
  EXPECT_EQ(c.step_halvings, 0);
}

}  // namespace
}  // namespace drape
