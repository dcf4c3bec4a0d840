// Which DIRK tables gain energy at 1/30 s, measured on the smallest cloth that shows it: a chain
// of 12 particles on bending-free springs, pinned at one end and released horizontal
// (experiments/scenes/swinging_chain.json; docs/findings/energy_gaining_tables.md, "One spring is
// enough"). Every ARKODE DIRK table runs it for 6 s with its stages solved by the line-search
// Newton. A table settles when the chain ends below the energy it started with (those that do end
// within 1e-6 J of each other, having lost the 7.8e-4 J the swing released); the others end 29 to
// 2000 times that above it, or diverge. The tables that settle are exactly those with |A_I^-1|_inf
// below 100 (table_stability.hpp): the measured counterpart of
// TableStability.ImplicitInverseNormSeparatesTheTablesThatGainEnergy, whose list of tables comes
// from the sheet.
#include <gtest/gtest.h>

#include <filesystem>

#include "core/scene/scene.hpp"
#include "experiments/run/scene_simulation.hpp"
#include "integrators/arkode/arkode_tables.hpp"
#include "integrators/arkode/butcher_tableau.hpp"
#include "integrators/arkode/table_stability.hpp"

namespace drape {
namespace {

const std::filesystem::path chain_scene =
    std::filesystem::path(DRAPE_SOURCE_DIR) / "experiments" / "scenes" / "swinging_chain.json";

struct ChainRun {
  bool finished = false;  // ran the 6 s without diverging
  double energy_change = 0.0;
};

ChainRun run_chain(const std::string& table) {
  SceneSimulation run(
      load_scene(chain_scene.string(), {"cloth.cols=12", "integrator.table=" + table}));
  const ClothSystem& system = run.system();
  const int n = system.num_particles();
  const auto energy = [&] {
    const Eigen::VectorXd& y = run.simulation().state();
    return system.energy(y.head(3 * n), y.tail(3 * n)).total();
  };
  const double start = energy();
  ChainRun out;
  out.finished = run.simulation().run().status == "ok";
  out.energy_change = energy() - start;
  return out;
}

TEST(SpringChainTables, TheTablesThatSettleAreThoseWithSmallImplicitInverseNorm) {
  int tables = 0;
  for (const ArkodeTable& table : arkode_tables()) {
    if (table.kind != ArkodeKind::diagonally_implicit) continue;
    ++tables;
    const double inverse_norm =
        table_stability(detail::to_butcher_tableau(detail::load_implicit_table(table).get()))
            .implicit_inverse_norm;
    const ChainRun run = run_chain(table.name);
    const bool settles = run.finished && run.energy_change < 0.0;
    EXPECT_EQ(settles, inverse_norm < 100.0)
        << table.name << ": |A_I^-1| " << inverse_norm << ", "
        << (run.finished ? "energy change " + std::to_string(run.energy_change) + " J"
                         : std::string("diverged"));
  }
  EXPECT_EQ(tables, 23);
}

}  // namespace
}  // namespace drape
