#include "experiments/sweep/child_runs.hpp"

#include <fmt/format.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <map>
#include <stdexcept>
#include <thread>

namespace drape {

namespace {

ChildEnd child_end(int status) {
  ChildEnd end;
  if (WIFEXITED(status)) {
    end.exited = true;
    end.exit_code = WEXITSTATUS(status);
  } else if (WIFSIGNALED(status)) {
    end.signal = WTERMSIG(status);
  }
  return end;
}

// sigabbrev_np is glibc >= 2.32 only; these are the signals a run dies of in practice.
const char* signal_name(int signal) {
  switch (signal) {
    case SIGSEGV: return "SIGSEGV";
    case SIGABRT: return "SIGABRT";
    case SIGBUS: return "SIGBUS";
    case SIGFPE: return "SIGFPE";
    case SIGILL: return "SIGILL";
    case SIGKILL: return "SIGKILL";
    case SIGTERM: return "SIGTERM";
    case SIGINT: return "SIGINT";
    case SIGXCPU: return "SIGXCPU";
    default: return "?";
  }
}

}  // namespace

std::string describe_child_end(const ChildEnd& end) {
  if (end.exited) return fmt::format("exit status {}", end.exit_code);
  const std::string reason = fmt::format("signal {} ({})", end.signal, signal_name(end.signal));
  // The kernel's out-of-memory killer and a hit RLIMIT_AS both end in SIGKILL without a word.
  return end.signal == SIGKILL ? reason + ", perhaps out of memory" : reason;
}

void run_in_children(std::size_t count, std::size_t jobs, const std::function<int(std::size_t)>& task,
                     const std::function<void(std::size_t, const ChildEnd&)>& on_end,
                     const std::function<void(std::size_t)>& on_start,
                     const std::function<void()>& on_tick, std::chrono::milliseconds tick_period) {
  jobs = std::max<std::size_t>(1, jobs);
  std::map<pid_t, std::size_t> running;
  // Reaps one ended child (blocking or not); true when it was one of ours.
  auto reap = [&](bool block) {
    int status = 0;
    pid_t pid;
    do pid = ::waitpid(-1, &status, block ? 0 : WNOHANG);
    while (pid < 0 && errno == EINTR);
    if (pid < 0) throw std::runtime_error(std::string("waitpid: ") + std::strerror(errno));
    const auto it = pid > 0 ? running.find(pid) : running.end();
    if (it == running.end()) return false;  // none ended, or not ours (a caller's child)
    const std::size_t k = it->second;
    running.erase(it);
    on_end(k, child_end(status));
    return true;
  };
  // With a tick the parent polls: a timer without a thread (a forking process should have one)
  // and without signals. A child's end is seen within one poll, which costs nothing.
  constexpr std::chrono::milliseconds poll_period{20};
  auto next_tick = std::chrono::steady_clock::now();
  auto wait_one = [&] {
    if (!on_tick) {
      while (!reap(true)) {}
      return;
    }
    while (!reap(false)) {
      const auto now = std::chrono::steady_clock::now();
      if (now >= next_tick) {
        on_tick();
        next_tick = now + tick_period;
      }
      std::this_thread::sleep_for(poll_period);
    }
  };
  for (std::size_t k = 0; k < count; ++k) {
    while (running.size() >= jobs) wait_one();
    if (on_start) on_start(k);
    // Buffered output would otherwise be written twice, once by each process.
    std::cout.flush();
    std::cerr.flush();
    std::fflush(nullptr);
    const pid_t parent = ::getpid();
    const pid_t pid = ::fork();
    if (pid < 0) {
      const std::string message = std::string("fork: ") + std::strerror(errno);
      while (!running.empty()) wait_one();
      throw std::runtime_error(message);
    }
    if (pid == 0) {
      // A run ends with the experiment: killed by its process id (SIGTERM, SIGINT to it alone,
      // not to the terminal's group), the parent left its runs going on alone, and a resume
      // started meanwhile wrote the same run folders at once. The check after prctl catches a
      // parent that died before it.
      ::prctl(PR_SET_PDEATHSIG, SIGKILL);
      if (::getppid() != parent) ::_exit(70);
      int code = 70;  // EX_SOFTWARE: the task threw past its own handler
      try {
        code = task(k);
      } catch (...) {
      }
      std::cout.flush();
      std::cerr.flush();
      std::fflush(nullptr);
      ::_exit(code);  // not exit: the parent's atexit handlers and static destructors are its own
    }
    running.emplace(pid, k);
  }
  while (!running.empty()) wait_one();
}

}  // namespace drape
