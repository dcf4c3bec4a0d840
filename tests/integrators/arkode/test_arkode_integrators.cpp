// The three ARKODE integrators: one per kind, found by name, each kind with its tables.
#include <gtest/gtest.h>

#include "integrators/arkode/arkode_integrators.hpp"

namespace drape {
namespace {

TEST(ArkodeIntegrators, OneIntegratorPerKindFoundByItsName) {
  ASSERT_EQ(arkode_integrators().size(), 3u);
  for (const ArkodeIntegrator& a : arkode_integrators()) {
    EXPECT_EQ(arkode_kind(a.name), a.kind) << a.name;
    EXPECT_STREQ(arkode_integrator(a.kind).name, a.name);
    // Only the implicit kinds solve stages, and only IMEX splits the forces.
    EXPECT_EQ(a.named_keys.newton_stages, a.kind != ArkodeKind::explicit_rk) << a.name;
    EXPECT_EQ(a.named_keys.imex_split, a.kind == ArkodeKind::imex) << a.name;
  }
  EXPECT_FALSE(arkode_kind("implicit-euler").has_value());
}

TEST(ArkodeIntegrators, TableNamesListEveryTableOfTheKindInOrder) {
  for (const ArkodeIntegrator& a : arkode_integrators()) {
    std::string expected;
    for (const ArkodeTable& table : arkode_tables())
      if (table.kind == a.kind) expected += (expected.empty() ? "" : ", ") + table.name;
    EXPECT_FALSE(expected.empty()) << a.name;
    EXPECT_EQ(arkode_table_names(a.kind), expected) << a.name;
  }
}

}  // namespace
}  // namespace drape
