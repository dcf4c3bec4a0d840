// The rows of the results table: what a result.json read back must be to count as a run's result.
#include "experiments/sweep/results_table.hpp"

#include <gtest/gtest.h>

namespace {

using nlohmann::json;

json valid_row() { return {{"id", "run_a"}, {"run_dir", "runs/run_a"}, {"status", "diverged"}}; }

TEST(ResultRowProblem, AcceptsEveryKnownStatus) {
  json row = valid_row();
  for (const char* status : {"ok", "diverged", "failed", "error", "crashed"}) {
    row["status"] = status;
    EXPECT_EQ(drape::result_row_problem(row, "run_a"), "") << status;
  }
}

TEST(ResultRowProblem, NamesWhatIsWrong) {
  EXPECT_EQ(drape::result_row_problem(json::array({1, 2}), "run_a"),
            "is a JSON array, not an object");
  EXPECT_EQ(drape::result_row_problem(json::object(), "run_a"),
            "\"id\" is missing, not the run's id \"run_a\"");
  EXPECT_EQ(drape::result_row_problem(valid_row(), "run_b"),
            "\"id\" is \"run_a\", not the run's id \"run_b\"");
  json moved = valid_row();
  moved["run_dir"] = "";
  EXPECT_EQ(drape::result_row_problem(moved, "run_a"), "\"run_dir\" is \"\", not \"runs/run_a\"");
  json banana = valid_row();
  banana["status"] = "banana";
  EXPECT_EQ(drape::result_row_problem(banana, "run_a"),
            "\"status\" is \"banana\", not one of ok, diverged, failed, error, crashed");
  banana.erase("status");
  EXPECT_EQ(drape::result_row_problem(banana, "run_a"),
            "\"status\" is missing, not one of ok, diverged, failed, error, crashed");
}

}  // namespace
