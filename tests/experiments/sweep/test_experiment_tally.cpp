// The counts of one experiment invocation, in the words the progress line and the final line
// share (docs/experiments.md, "Parallel runs, progress, resume").
#include "experiments/sweep/experiment_tally.hpp"

#include <gtest/gtest.h>

namespace drape {
namespace {

TEST(ExperimentTally, EachStatusHasItsCountAndEveryOtherIsAResult) {
  ExperimentTally t;
  t.planned = 9;
  t.skipped = 2;
  for (const char* status : {"ok", "ok", "ok", "diverged", "failed", "error", "crashed"})
    t.count(status);
  EXPECT_EQ(t.ok, 3);
  EXPECT_EQ(t.unstable, 2) << "diverged and failed are results of the run";
  EXPECT_EQ(t.errors, 1);
  EXPECT_EQ(t.crashed, 1);
  EXPECT_EQ(t.done(), 9);
  EXPECT_EQ(t.summary(), "3 ok, 2 diverged or failed, 1 could not run, 1 crashed, 2 resumed");
}

TEST(ExperimentTally, NothingRunYet) {
  const ExperimentTally t;
  EXPECT_EQ(t.done(), 0);
  EXPECT_EQ(t.summary(), "0 ok, 0 diverged or failed, 0 could not run, 0 crashed, 0 resumed");
}

}  // namespace
}  // namespace drape
