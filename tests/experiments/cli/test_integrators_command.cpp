// `drapelab integrators --table`: every arkode-dirk table printed as the inline tableau that
// `integrator.table` accepts, exactly ARKODE's coefficients, and a run with it the same run
// as with the table's name (docs/integrators/arkode.md, "User tables"); `--stability`: the explicit
// steps' limit on a scene (docs/model.md, "Stability limit").
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <nlohmann/json.hpp>

#include "integrators/arkode/arkode_tables.hpp"
#include "integrators/arkode/butcher_tableau.hpp"
#include "tests/support/drapelab_process.hpp"

namespace drape {
namespace {

using testing::run_drapelab;

TEST(IntegratorsCommand, PrintsSdirk2AsItsTableau) {
  const auto result = run_drapelab("integrators --table ARKODE_SDIRK_2_1_2");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  // ARKODE's SDIRK_2_1_2 (docs/findings/energy_gaining_tables.md, "Which tables gain energy at
  // large steps").
  EXPECT_EQ(nlohmann::json::parse(result.out), nlohmann::json::parse(R"({
    "A": [[1.0, 0.0], [-1.0, 1.0]], "b": [0.5, 0.5], "c": [1.0, 0.0], "d": [1.0, 0.0],
    "q": 2, "p": 1})"));
}

TEST(IntegratorsCommand, EveryDirkTableReadsBackAsTheSameCoefficients) {
  int tables = 0;
  for (const ArkodeTable& table : arkode_tables()) {
    if (table.kind != ArkodeKind::diagonally_implicit) continue;
    ++tables;
    const auto result = run_drapelab("integrators --table " + table.name);
    ASSERT_EQ(result.exit_code, 0) << table.name << ": " << result.err;
    // The user-table reader checks consistency and the stated orders (up to 3).
    const ButcherTableau printed =
        read_butcher_tableau(nlohmann::json::parse(result.out), "stdout", "integrator.table");
    const ButcherTableau arkode =
        detail::to_butcher_tableau(detail::load_implicit_table(table).get());
    EXPECT_EQ(printed.A, arkode.A) << table.name;
    EXPECT_EQ(printed.b, arkode.b) << table.name;
    EXPECT_EQ(printed.c, arkode.c) << table.name;
    EXPECT_EQ(printed.d, arkode.d) << table.name;
    EXPECT_EQ(printed.q, arkode.q) << table.name;
    EXPECT_EQ(printed.p, arkode.p) << table.name;
  }
  EXPECT_EQ(tables, 23);
}

TEST(IntegratorsCommand, RunWithThePrintedTableIsTheRunWithItsName) {
  const std::string printed = run_drapelab("integrators --table ARKODE_KVAERNO_4_2_3").out;
  const std::filesystem::path dir =
      std::filesystem::path(::testing::TempDir()) / "integrators_command_round_trip";
  std::filesystem::remove_all(dir);
  const std::string run = "run " + std::string(DRAPE_SOURCE_DIR) +
                          "/experiments/scenes/swinging_chain.json -q --set cloth.cols=2 "
                          "--set duration=0.5 --out ";
  ASSERT_EQ(run_drapelab(run + (dir / "named").string() +
                         " --set integrator.table=ARKODE_KVAERNO_4_2_3")
                .exit_code,
            0);
  ASSERT_EQ(run_drapelab(run + (dir / "inline").string() + " --set 'integrator.table=" +
                         printed.substr(0, printed.find('\n')) + "'")
                .exit_code,
            0);
  const std::string named = testing::read_text(dir / "named" / "state.csv");
  EXPECT_FALSE(named.empty());
  EXPECT_EQ(testing::read_text(dir / "inline" / "state.csv"), named);
}

TEST(IntegratorsCommand, NamesTheOptionForATableThatIsNotDirk) {
  for (const std::string name : {"KVAERNO", "ARKODE_BOGACKI_SHAMPINE_4_2_3", ""}) {
    const auto result = run_drapelab("integrators --table '" + name + "'");
    EXPECT_EQ(result.exit_code, 2) << name;
    EXPECT_NE(result.err.find("--table"), std::string::npos) << result.err;
    EXPECT_NE(result.err.find(name), std::string::npos) << result.err;
    EXPECT_TRUE(result.out.empty()) << result.out;
  }
}

// The drape scene's cloth at rest: k = 50 N/m, c_s = 0.01 N s/m, c_air = 1e-4 N s/m, m = 6e-5 kg,
// so c = (c_s / k) omega^2 + c_air / m and the printed limit is the positive root of
// dt^2 omega^2 + 2 dt c = 4; a bad --set is named.
TEST(IntegratorsCommand, PrintsTheStabilityLimitOfTheDrapeScene) {
  const std::string scene =
      std::string(DRAPE_SOURCE_DIR) + "/experiments/scenes/drape_dress_form.json";
  const auto result = run_drapelab("integrators --stability " + scene);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  double omega = 0.0, c = 0.0, damped = 0.0, undamped = 0.0;
  const auto at = [&](const std::string& key) {
    const auto k = result.out.find(key);
    EXPECT_NE(k, std::string::npos) << key << " in " << result.out;
    return std::stod(result.out.substr(k + key.size()));
  };
  omega = at("omega = ");
  c = at("c = ");
  damped = at("stable below dt = ") * 1e-3;
  undamped = at("2 / omega = ") * 1e-3;
  EXPECT_NEAR(c, 0.01 / 50.0 * omega * omega + 1e-4 / 6e-5, 1e-5 * c);
  EXPECT_NEAR(undamped, 2.0 / omega, 1e-5 * undamped);
  EXPECT_NEAR(damped, (-c + std::sqrt(c * c + 4.0 * omega * omega)) / (omega * omega),
              1e-5 * damped);
  // Measured by bisection (docs/integrators/explicit.md, "Largest stable fixed step"): 0.591-0.604
  // ms.
  EXPECT_GT(damped, 0.591e-3);
  EXPECT_LT(damped, 0.604e-3);

  const auto bad = run_drapelab("integrators --stability " + scene + " --set cloth.nope=1");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("--set cloth.nope=1"), std::string::npos) << bad.err;
  // Options that would be ignored are refused.
  const auto alone = run_drapelab("integrators --set duration=1");
  EXPECT_EQ(alone.exit_code, 2);
  EXPECT_NE(alone.err.find("--set requires --stability"), std::string::npos) << alone.err;
  const auto both = run_drapelab("integrators --stability " + scene + " --table ARKODE_SDIRK_2_1_2");
  EXPECT_EQ(both.exit_code, 2);
  EXPECT_NE(both.err.find("excludes"), std::string::npos) << both.err;
}

}  // namespace
}  // namespace drape
