#include "experiments/live/connection_threads.hpp"

namespace drape {

ConnectionThreads::~ConnectionThreads() { shutdown(); }

void ConnectionThreads::enqueue(std::function<void()> task) {
  {
    std::lock_guard<std::mutex> lock(m_mutex);
    m_tasks.push_back(std::move(task));
    // A waiting thread counts as idle until it takes a task (under this lock), so every queued
    // task beyond the idle threads is one no thread would take now.
    if (m_tasks.size() > m_idle && m_threads.size() < m_max_threads)
      m_threads.emplace_back([this] { work(); });
  }
  m_ready.notify_one();
}

void ConnectionThreads::shutdown() {
  {
    std::lock_guard<std::mutex> lock(m_mutex);
    m_shutdown = true;
  }
  m_ready.notify_all();
  // Only the listening thread enqueues, and it has stopped: the list no longer grows.
  for (std::thread& t : m_threads)
    if (t.joinable()) t.join();
}

std::size_t ConnectionThreads::threads() const {
  std::lock_guard<std::mutex> lock(m_mutex);
  return m_threads.size();
}

void ConnectionThreads::work() {
  for (;;) {
    std::function<void()> task;
    {
      std::unique_lock<std::mutex> lock(m_mutex);
      ++m_idle;
      m_ready.wait(lock, [this] { return !m_tasks.empty() || m_shutdown; });
      --m_idle;
      if (m_tasks.empty()) return;  // shut down, nothing left to run
      task = std::move(m_tasks.front());
      m_tasks.pop_front();
    }
    task();
  }
}

}  // namespace drape
