// The test hook that crashes an experiment's run on purpose (docs/experiments.md, "Isolation"):
// nothing without DRAPELAB_TEST_CRASH, every run or only the runs whose id holds the given part,
// by the signal asked for.
#include "experiments/sweep/deliberate_crash.hpp"

#include <gtest/gtest.h>

#include <csignal>
#include <cstdlib>

namespace drape {
namespace {

/// Sets DRAPELAB_TEST_CRASH for one test, and unsets it after.
class CrashRequest {
 public:
  explicit CrashRequest(const char* value) { setenv("DRAPELAB_TEST_CRASH", value, 1); }
  ~CrashRequest() { unsetenv("DRAPELAB_TEST_CRASH"); }
  CrashRequest(const CrashRequest&) = delete;
  CrashRequest& operator=(const CrashRequest&) = delete;
};

TEST(DeliberateCrash, NothingHappensUnlessAskedOrForAnotherRun) {
  unsetenv("DRAPELAB_TEST_CRASH");
  crash_if_asked_for_test("dt-0.001-ab12");
  {
    const CrashRequest other_run("abort:dt-0.002");
    crash_if_asked_for_test("dt-0.001-ab12");
  }
  const CrashRequest unknown_kind("explode");
  crash_if_asked_for_test("dt-0.001-ab12");
  SUCCEED() << "still running";
}

TEST(DeliberateCrashDeathTest, TheRunAskedForDiesByTheSignalAskedFor) {
  {
    const CrashRequest one_run("abort:0.001");
    EXPECT_EXIT(crash_if_asked_for_test("dt-0.001-ab12"), ::testing::KilledBySignal(SIGABRT), "");
  }
  const CrashRequest every_run("segv");
  EXPECT_EXIT(crash_if_asked_for_test("dt-0.002-cd34"), ::testing::KilledBySignal(SIGSEGV), "");
}

}  // namespace
}  // namespace drape
