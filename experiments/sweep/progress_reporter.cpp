#include "experiments/sweep/progress_reporter.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace drape {

namespace {

std::string clock(double seconds) {
  const long s = std::lround(seconds);
  return s >= 3600 ? fmt::format("{}:{:02d}:{:02d}", s / 3600, s / 60 % 60, s % 60)
                   : fmt::format("{}:{:02d}", s / 60, s % 60);
}

std::string fit(std::string line, int width) {
  if (static_cast<int>(line.size()) > width) line.resize(static_cast<std::size_t>(width));
  return line;
}

// Redraws are for people: twice a second is smooth enough and costs nothing.
constexpr std::chrono::milliseconds redraw_period{500};
// Running runs shown below the bar; more are summed up in one line.
constexpr std::size_t max_running_lines = 8;

}  // namespace

ProgressReporter::ProgressReporter(int total, ProgressStyle style, std::ostream& out)
    : m_total(total), m_style(style), m_out(out), m_start(std::chrono::steady_clock::now()) {
  if (m_style == ProgressStyle::Terminal) m_redraw = std::thread([this] { redraw_loop(); });
}

ProgressReporter::~ProgressReporter() { finish(); }

void ProgressReporter::run_started(const std::string& id) {
  const std::lock_guard<std::mutex> lock(m_mutex);
  m_running[id] = 0.0;
}

void ProgressReporter::run_progress(const std::string& id, double fraction) {
  const std::lock_guard<std::mutex> lock(m_mutex);
  m_running[id] = std::clamp(fraction, 0.0, 1.0);
}

void ProgressReporter::run_finished(const std::string& id, const std::string& status,
                                    bool resumed) {
  const std::lock_guard<std::mutex> lock(m_mutex);
  m_running.erase(id);
  if (resumed) ++m_resumed;
  else if (status == "ok") ++m_ok;
  else if (status == "error") ++m_errors;
  else ++m_unstable;
  if (m_style != ProgressStyle::Lines) return;
  const int done = m_ok + m_unstable + m_errors + m_resumed;
  const double left = seconds_left_locked();
  m_out << fmt::format("drapelab: [{}/{}] {} {}{}, {} elapsed{}\n", done, m_total, id, status,
                       resumed ? " (resumed)" : "",
                       clock(std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                                           m_start).count()),
                       left >= 0.0 ? ", ~" + clock(left) + " left" : "")
        << std::flush;
}

void ProgressReporter::finish() {
  {
    const std::lock_guard<std::mutex> lock(m_mutex);
    if (m_stop) return;
    m_stop = true;
  }
  m_wake.notify_all();
  if (m_redraw.joinable()) m_redraw.join();
  if (m_style == ProgressStyle::Terminal) {
    const std::lock_guard<std::mutex> lock(m_mutex);
    draw_locked();
    m_out << "\n" << std::flush;
  }
}

double ProgressReporter::seconds_left() const {
  const std::lock_guard<std::mutex> lock(m_mutex);
  return seconds_left_locked();
}

std::vector<std::string> ProgressReporter::block(int width) const {
  const std::lock_guard<std::mutex> lock(m_mutex);
  return block_locked(width);
}

double ProgressReporter::seconds_left_locked() const {
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count();
  // Resumed runs cost nothing now: they are neither work done nor work left.
  const double work = m_total - m_resumed;
  double done = m_ok + m_unstable + m_errors;
  for (const auto& [id, fraction] : m_running) done += fraction;
  if (done <= 0.0) return -1.0;
  return elapsed * std::max(0.0, work - done) / done;
}

std::vector<std::string> ProgressReporter::block_locked(int width) const {
  const int done = m_ok + m_unstable + m_errors + m_resumed;
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count();
  const double left = seconds_left_locked();
  const int bar = 20;
  const int filled = m_total > 0 ? bar * done / m_total : bar;
  std::vector<std::string> lines;
  lines.push_back(fit(fmt::format("[{}{}] {}/{}  ok {}  unstable {}  error {}  {}  ~{} left",
                                  std::string(static_cast<std::size_t>(filled), '#'),
                                  std::string(static_cast<std::size_t>(bar - filled), '-'), done,
                                  m_total, m_ok + m_resumed, m_unstable, m_errors, clock(elapsed),
                                  left >= 0.0 ? clock(left) : "--:--"),
                      width));
  const int id_width = std::max(8, width - 2 - 6);
  for (const auto& [id, fraction] : m_running) {
    if (lines.size() > max_running_lines) {
      lines.push_back(fit(fmt::format("  ... and {} more running",
                                      m_running.size() - max_running_lines),
                          width));
      break;
    }
    lines.push_back(fit(fmt::format("  {:<{}} {:>4.0f}%", fit(id, id_width), id_width,
                                    100.0 * fraction),
                        width));
  }
  return lines;
}

void ProgressReporter::redraw_loop() {
  std::unique_lock<std::mutex> lock(m_mutex);
  while (!m_stop) {
    draw_locked();
    m_wake.wait_for(lock, redraw_period, [this] { return m_stop; });
  }
}

void ProgressReporter::draw_locked() {
  // Back to the block's first line, clear to the end of the screen, draw it again; the cursor
  // stays at the end of the last line so nothing scrolls.
  if (m_drawn_lines > 1) m_out << fmt::format("\x1b[{}A", m_drawn_lines - 1);
  m_out << "\r\x1b[J";
  const std::vector<std::string> lines = block_locked(79);
  for (std::size_t i = 0; i < lines.size(); ++i) m_out << (i ? "\n" : "") << lines[i];
  m_out << std::flush;
  m_drawn_lines = static_cast<int>(lines.size());
}

void RunProgressObserver::report(const Simulation& simulation) {
  const double duration = simulation.settings().duration;
  const double fraction = duration > 0.0 ? simulation.time() / duration : 1.0;
  if (fraction - m_reported < 0.01 && fraction < 1.0) return;
  m_reported = fraction;
  m_reporter.run_progress(m_id, fraction);
}

}  // namespace drape
