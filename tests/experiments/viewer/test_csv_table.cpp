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

// inf, nan and 1e12 are numbers to from_chars; finite() and integer() refuse them where they
// are damage (a cast of nan or 1e12 to int is undefined behaviour), naming file, line, column.
TEST(CsvTable, CheckedReadsNameFileLineAndColumn) {
  const auto dir = testing::fresh_folder("csv_checked");
  testing::write_text(dir / "a.csv", "t,n\n0.5,3\n\ninf,nan\n1,1e12\n-2,0.5\n");
  const CsvTable table(dir / "a.csv", {"t", "n"});
  const std::string file = (dir / "a.csv").string();
  EXPECT_EQ(table.finite(0, 0), 0.5);
  EXPECT_EQ(table.integer(0, 1, 0, 3), 3);
  EXPECT_EQ(table.integer(3, 0, -2, 0), -2);
  // The blank line 3 is skipped: row 1 is line 4.
  EXPECT_EQ(input_error_message([&] { table.finite(1, 0); }),
            file + ": line 4: column 't' is not a finite number: inf");
  EXPECT_EQ(input_error_message([&] { table.integer(1, 1, 0, 10); }),
            file + ": line 4: column 'n' is nan, expected an integer in [0, 10]");
  EXPECT_EQ(input_error_message([&] { table.integer(2, 1, 0, 10); }),
            file + ": line 5: column 'n' is 1000000000000, expected an integer in [0, 10]");
  EXPECT_EQ(input_error_message([&] { table.integer(3, 1, 0, 10); }),
            file + ": line 6: column 'n' is 0.5, expected an integer in [0, 10]");
  EXPECT_EQ(input_error_message([&] { table.integer(0, 1, 0, 2); }),
            file + ": line 2: column 'n' is 3, expected an integer in [0, 2]");
}

}  // namespace
}  // namespace drape
