#pragma once
// The live server's task queue (docs/live.md, "Many connections"): each connection cpp-httplib
// accepts gets a thread of its own at once, so no request waits for another connection to end.
// A fixed pool (httplib::ThreadPool) is held whole by as many open event streams or idle sockets
// as it has workers, and `POST /key` then waits seconds behind them.
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

// Last in every file that includes it: its system headers define macros that Eigen's
// templates (through the scene) trip over.
#include <httplib.h>

namespace drape {

/// httplib's TaskQueue with a thread for every task running at once, up to `max_threads`:
/// a thread is started when every one started so far is busy, and stays for later tasks.
/// Beyond `max_threads` busy threads a task waits for one of them, as in a fixed pool.
class ConnectionThreads : public httplib::TaskQueue {
 public:
  explicit ConnectionThreads(std::size_t max_threads) : m_max_threads(max_threads) {}
  ~ConnectionThreads() override;

  void enqueue(std::function<void()> task) override;
  /// Runs the tasks still queued, then joins every thread.
  void shutdown() override;
  /// Threads started so far (the most tasks that ran at once, up to max_threads).
  std::size_t threads() const;

 private:
  void work();

  const std::size_t m_max_threads;
  mutable std::mutex m_mutex;  ///< guards the members below
  std::condition_variable m_ready;
  std::deque<std::function<void()>> m_tasks;
  std::vector<std::thread> m_threads;
  std::size_t m_idle = 0;  ///< threads waiting for a task
  bool m_shutdown = false;
};

}  // namespace drape
