// Child processes per run: exit codes and signals reach the parent (docs/experiments.md).
#include "experiments/sweep/child_runs.hpp"

#include <gtest/gtest.h>

#include <csignal>
#include <cstdlib>
#include <map>

namespace {

TEST(ChildRuns, EveryTaskEndsOnceWithItsExitCodeOrSignal) {
  std::map<std::size_t, drape::ChildEnd> ends;
  drape::run_in_children(
      5, 2,
      [](std::size_t k) {
        if (k == 3) {
          std::signal(SIGSEGV, SIG_DFL);  // past any sanitizer's handler
          std::raise(SIGSEGV);
        }
        if (k == 4) std::abort();
        return static_cast<int>(k);
      },
      [&](std::size_t k, const drape::ChildEnd& end) { EXPECT_TRUE(ends.emplace(k, end).second); });
  ASSERT_EQ(ends.size(), 5u);
  EXPECT_TRUE(ends[0].ok());
  EXPECT_EQ(drape::describe_child_end(ends[2]), "exit status 2");
  EXPECT_FALSE(ends[2].ok());
  EXPECT_EQ(drape::describe_child_end(ends[3]), "signal 11 (SIGSEGV)");
  EXPECT_EQ(drape::describe_child_end(ends[4]), "signal 6 (SIGABRT)");
}

TEST(ChildRuns, AKilledChildMayHaveRunOutOfMemory) {
  drape::ChildEnd end;
  end.signal = SIGKILL;
  EXPECT_EQ(drape::describe_child_end(end), "signal 9 (SIGKILL), perhaps out of memory");
}

}  // namespace
