// `drapelab integrators --table`: every arkode-dirk table printed as the inline tableau that
// `integrator.table` accepts, exactly ARKODE's coefficients, and a run with it the same run
// as with the table's name (docs/integrators.md, "User tables").
#include <gtest/gtest.h>

#include <filesystem>
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
  // ARKODE's SDIRK_2_1_2 (docs/integrators.md, "Which tables gain energy at large steps").
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

}  // namespace
}  // namespace drape
