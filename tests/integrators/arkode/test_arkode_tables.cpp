// The ARKODE tables drapelab accepts as `integrator.table`: each name found with its kind only,
// each loading from SUNDIALS as its name says (ARKODE's NAME_s_p_q: stages, embedded order,
// order), an IMEX pair's halves of the same stages and orders, the defaults among them.
#include "integrators/arkode/arkode_tables.hpp"

#include <gtest/gtest.h>

#include <set>

namespace drape {
namespace {

/// The trailing numbers of a table's name: {s, p, q}, or {s, q} without an embedding.
std::vector<int> name_numbers(const std::string& name) {
  std::vector<int> numbers;
  std::size_t end = name.size();
  while (end > 0) {
    const std::size_t start = name.rfind('_', end - 1);
    const std::string part = name.substr(start + 1, end - start - 1);
    if (part.empty() || part.find_first_not_of("0123456789") != std::string::npos) break;
    numbers.insert(numbers.begin(), std::stoi(part));
    end = start;
  }
  return numbers;
}

TEST(ArkodeTables, EachTableLoadsAsItsNameSays) {
  std::set<std::string> names;
  int kind_order = 0;
  for (const ArkodeTable& table : arkode_tables()) {
    SCOPED_TRACE(table.name);
    EXPECT_TRUE(names.insert(table.name).second) << "listed once";
    EXPECT_GE(static_cast<int>(table.kind), kind_order) << "ERK, then DIRK, then IMEX";
    kind_order = static_cast<int>(table.kind);
    EXPECT_EQ(table.explicit_table.empty(), table.kind == ArkodeKind::diagonally_implicit);
    EXPECT_EQ(table.implicit_table.empty(), table.kind == ArkodeKind::explicit_rk);
    const auto main = detail::load_main_table(table);
    ASSERT_NE(main, nullptr);
    const std::vector<int> numbers = name_numbers(table.name);
    ASSERT_GE(numbers.size(), 2u);
    EXPECT_EQ(main->stages, numbers.front());
    EXPECT_EQ(main->q, numbers.back());
    if (numbers.size() == 3) EXPECT_EQ(main->p, numbers[1]);
    if (table.kind == ArkodeKind::imex) {
      const auto explicit_half = detail::load_explicit_table(table);
      ASSERT_NE(explicit_half, nullptr);
      EXPECT_EQ(explicit_half->stages, main->stages);
      EXPECT_EQ(explicit_half->q, main->q);
    }
  }
  EXPECT_EQ(names.size(), 15u + 23u + 5u);
}

TEST(ArkodeTables, ANameIsFoundOnlyWithItsKind) {
  ASSERT_NE(find_arkode_table("ARKODE_KVAERNO_4_2_3", ArkodeKind::diagonally_implicit), nullptr);
  EXPECT_EQ(find_arkode_table("ARKODE_KVAERNO_4_2_3", ArkodeKind::explicit_rk), nullptr);
  EXPECT_EQ(find_arkode_table("KVAERNO_4_2_3", ArkodeKind::diagonally_implicit), nullptr)
      << "the full ARKODE name";
  const ArkodeTable* pair = find_arkode_table("ARKODE_ARK548L2SAb_8_4_5", ArkodeKind::imex);
  ASSERT_NE(pair, nullptr);
  EXPECT_EQ(pair->explicit_table, "ARKODE_ARK548L2SAb_ERK_8_4_5");
  EXPECT_EQ(pair->implicit_table, "ARKODE_ARK548L2SAb_DIRK_8_4_5");
  for (const ArkodeKind kind :
       {ArkodeKind::explicit_rk, ArkodeKind::diagonally_implicit, ArkodeKind::imex})
    EXPECT_NE(find_arkode_table(default_arkode_table(kind), kind), nullptr)
        << default_arkode_table(kind);
}

}  // namespace
}  // namespace drape
