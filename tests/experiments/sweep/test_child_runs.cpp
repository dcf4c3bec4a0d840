// Child processes per run: exit codes and signals reach the parent (docs/experiments.md).
#include "experiments/sweep/child_runs.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <thread>

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

TEST(ChildRuns, TheParentTicksWhileItsChildrenRun) {
  // Each child runs until the parent's tick has written its go file: it can only end with status
  // 0 if the parent ticked while it ran (exit 1 after 20 s without one).
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(::testing::TempDir()) / "child_runs_tick";
  fs::remove_all(dir);
  fs::create_directories(dir);
  auto go = [&](std::size_t k) { return dir / ("go" + std::to_string(k)); };
  std::map<std::size_t, drape::ChildEnd> ends;
  int ticks = 0;
  drape::run_in_children(
      3, 2,
      [&](std::size_t k) {
        for (int i = 0; i < 2000; ++i) {
          if (fs::exists(go(k))) return 0;
          std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
        return 1;
      },
      [&](std::size_t k, const drape::ChildEnd& end) { ends.emplace(k, end); }, {},
      [&] {
        ++ticks;
        for (std::size_t k = 0; k < 3; ++k) std::ofstream(go(k)) << "go";
      },
      std::chrono::milliseconds(50));
  ASSERT_EQ(ends.size(), 3u);
  for (const auto& [k, end] : ends) EXPECT_TRUE(end.ok()) << k << ": " << drape::describe_child_end(end);
  EXPECT_GE(ticks, 1);
}

TEST(ChildRuns, AKilledChildMayHaveRunOutOfMemory) {
  drape::ChildEnd end;
  end.signal = SIGKILL;
  EXPECT_EQ(drape::describe_child_end(end), "signal 9 (SIGKILL), perhaps out of memory");
}

}  // namespace
