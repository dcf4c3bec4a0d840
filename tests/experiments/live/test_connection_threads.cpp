// The live server's task queue: every task running at once has a thread of its own up to the
// bound, beyond it a task waits, and shutdown runs what is queued (docs/live.md, "Many
// connections").
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <utility>

#include "experiments/live/connection_threads.hpp"

namespace {

// Tasks that count themselves started and then wait until the gate opens, as an event stream
// holds its connection's thread until the page closes.
class Gate {
 public:
  std::function<void()> task() {
    return [this] {
      std::unique_lock<std::mutex> lock(m_mutex);
      ++m_started;
      m_changed.notify_all();
      m_changed.wait(lock, [this] { return m_open; });
    };
  }
  /// Whether `n` tasks have started within 10 s.
  bool started(int n) {
    std::unique_lock<std::mutex> lock(m_mutex);
    return m_changed.wait_for(lock, std::chrono::seconds(10), [&] { return m_started >= n; });
  }
  int started_now() {
    std::lock_guard<std::mutex> lock(m_mutex);
    return m_started;
  }
  void open() {
    {
      std::lock_guard<std::mutex> lock(m_mutex);
      m_open = true;
    }
    m_changed.notify_all();
  }

 private:
  std::mutex m_mutex;
  std::condition_variable m_changed;
  int m_started = 0;
  bool m_open = false;
};

// Tasks held at a gate, as an event stream holds its connection's thread until the page
// closes: up to the bound each has its own thread at once (with a fixed pool of 64, 64 event
// streams left POST /key waiting for seconds), beyond it the others wait for one.
TEST(ConnectionThreads, EveryTaskRunningAtOnceHasAThreadUpToTheBound) {
  for (const auto& [bound, tasks] : {std::pair<std::size_t, int>{8, 8}, {2, 3}}) {
    SCOPED_TRACE(::testing::Message() << bound << " threads at most, " << tasks << " tasks");
    const int at_once = std::min(static_cast<int>(bound), tasks);
    drape::ConnectionThreads threads(bound);
    Gate gate;
    for (int i = 0; i < tasks; ++i) threads.enqueue(gate.task());
    EXPECT_TRUE(gate.started(at_once));
    EXPECT_EQ(threads.threads(), static_cast<std::size_t>(at_once));
    // Every thread waits at the gate, so no further task can have started.
    EXPECT_EQ(gate.started_now(), at_once);
    gate.open();
    EXPECT_TRUE(gate.started(tasks));
    threads.shutdown();
    EXPECT_EQ(threads.threads(), static_cast<std::size_t>(at_once));
  }
}

// httplib shuts the queue down once it stops accepting: a connection accepted just before must
// still be run, which closes its socket.
TEST(ConnectionThreads, ShutdownRunsTheQueuedTasks) {
  drape::ConnectionThreads threads(1);
  std::atomic<int> ran{0};
  for (int i = 0; i < 20; ++i) threads.enqueue([&ran] { ++ran; });
  threads.shutdown();
  EXPECT_EQ(ran.load(), 20);
  EXPECT_EQ(threads.threads(), 1u);
}

}  // namespace
