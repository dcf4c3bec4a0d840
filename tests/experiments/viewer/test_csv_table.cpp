#include <gtest/gtest.h>

#include "tests/support/test_support.hpp"
#include "experiments/viewer/csv_table.hpp"
#include "viewer_test_files.hpp"

namespace drape {
namespace {

using testing::input_error_message;

TEST(CsvTable, ReadsRequestedColumnsByName) {
  const auto dir = testing::fresh_folder("csv_ok");
  testing::write_text(dir / "a.csv", "t,hand,x\n0.5,left,1e-3\n1,right,-2\n");
  const CsvTable table(dir / "a.csv", {"x", "t"}, {"hand"});
  ASSERT_EQ(table.rows(), 2);
  EXPECT_EQ(table.at(0, 0), 1e-3);
  EXPECT_EQ(table.at(1, 1), 1.0);
  EXPECT_EQ(table.text(1, 0), "right");
}

TEST(CsvTable, MalformedInputNamesFileAndLine) {
  const auto dir = testing::fresh_folder("csv_bad");
  testing::write_text(dir / "a.csv", "t,x\n0,1\n1,oops\n");
  testing::write_text(dir / "b.csv", "t,x\n0,1,2\n");
  const std::string file_a = (dir / "a.csv").string(), file_b = (dir / "b.csv").string();
  EXPECT_EQ(input_error_message([&] { CsvTable(file_a, {"x"}); }),
            file_a + ": line 3: column 'x' is not a number: 'oops'");
  EXPECT_EQ(input_error_message([&] { CsvTable(file_a, {"y"}); }),
            file_a + ": line 1: no column 'y' in the header 't,x'");
  EXPECT_EQ(input_error_message([&] { CsvTable(file_b, {"x"}); }),
            file_b + ": line 2: expected 2 fields, got 3");
  EXPECT_NE(input_error_message([&] { CsvTable(dir / "none.csv", {"x"}); }).find("cannot read"),
            std::string::npos);
}

}  // namespace
}  // namespace drape
