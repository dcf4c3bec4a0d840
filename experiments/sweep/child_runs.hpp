#pragma once
// Runs tasks each in a forked child process, a few at a time, so that a run which crashes,
// aborts or is killed for memory ends only itself (docs/experiments.md, "Isolation").
#include <chrono>
#include <cstddef>
#include <functional>
#include <string>

namespace drape {

/// How a child ended, from waitpid's status.
struct ChildEnd {
  bool exited = false;  ///< returned from main or called exit
  int exit_code = 0;    ///< when exited
  int signal = 0;       ///< the signal that killed it, when not exited
  bool ok() const { return exited && exit_code == 0; }
};

/// "signal 11 (SIGSEGV)", "exit status 3": the reason a results row gives for a crashed run.
std::string describe_child_end(const ChildEnd& end);

/// Runs task(k) for k in [0, count) each in its own forked child, at most `jobs` at once; the
/// child's exit code is task's return value. on_start(k) and on_end(k, end) run in the calling
/// process, on_end in the order children end; on_tick, when given, every `tick_period` while
/// children run (the parent then polls them instead of blocking in waitpid). Call it from a
/// single-threaded process: only the forking thread lives on in the child.
void run_in_children(std::size_t count, std::size_t jobs, const std::function<int(std::size_t)>& task,
                     const std::function<void(std::size_t, const ChildEnd&)>& on_end,
                     const std::function<void(std::size_t)>& on_start = {},
                     const std::function<void()>& on_tick = {},
                     std::chrono::milliseconds tick_period = std::chrono::milliseconds(500));

}  // namespace drape
