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

// A run id too long for its line keeps its start (the scene) and its end (the last values and
// the hash that tell runs apart).
std::string elide_middle(const std::string& id, int width) {
  if (static_cast<int>(id.size()) <= width) return id;
  const std::size_t head = static_cast<std::size_t>((width - 3) / 2);
  const std::size_t tail = static_cast<std::size_t>(width - 3) - head;
  return id.substr(0, head) + "..." + id.substr(id.size() - tail);
}

// Running runs shown below the bar; more are summed up in one line.
constexpr std::size_t max_running_lines = 8;
// One column short of 80: a terminal that wraps at the last column scrolls otherwise.
constexpr int terminal_width = 79;

}  // namespace

ProgressReporter::ProgressReporter(int total, ProgressStyle style, std::ostream& out)
    : m_style(style), m_out(out), m_start(std::chrono::steady_clock::now()) {
  m_tally.planned = total;
}

ProgressReporter::~ProgressReporter() { finish(); }

void ProgressReporter::run_started(const std::string& id) { m_running[id] = 0.0; }

void ProgressReporter::run_progress(const std::string& id, double fraction) {
  const auto it = m_running.find(id);
  if (it != m_running.end()) it->second = std::clamp(fraction, 0.0, 1.0);
}

void ProgressReporter::run_finished(const std::string& id, const std::string& status,
                                    bool resumed) {
  m_running.erase(id);
  if (resumed) ++m_tally.skipped;
  else m_tally.count(status);
  if (m_style != ProgressStyle::Lines) return;
  const int done = m_tally.done();
  const double now = elapsed();
  const double left = seconds_left(now);
  m_out << fmt::format("drapelab: [{}/{}] {} {}{}, {} elapsed{}\n", done, m_tally.planned, id,
                       status, resumed ? " (resumed)" : "", clock(now),
                       left >= 0.0 ? ", ~" + clock(left) + " left" : "")
        << std::flush;
}

void ProgressReporter::redraw() {
  if (m_style != ProgressStyle::Terminal || m_finished) return;
  // Back to the block's first line, clear to the end of the screen, draw it again; the cursor
  // stays at the end of the last line so nothing scrolls.
  if (m_drawn_lines > 1) m_out << fmt::format("\x1b[{}A", m_drawn_lines - 1);
  m_out << "\r\x1b[J";
  const std::vector<std::string> lines = block(terminal_width, elapsed());
  for (std::size_t i = 0; i < lines.size(); ++i) m_out << (i ? "\n" : "") << lines[i];
  m_out << std::flush;
  m_drawn_lines = static_cast<int>(lines.size());
}

void ProgressReporter::finish() {
  if (m_finished) return;
  if (m_style == ProgressStyle::Terminal) {
    redraw();
    m_out << "\n" << std::flush;
  }
  m_finished = true;
}

double ProgressReporter::elapsed() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count();
}

double ProgressReporter::seconds_left(double elapsed) const {
  // Resumed runs cost nothing now: they are neither work done nor work left.
  const double work = m_tally.planned - m_tally.skipped;
  double done = m_tally.done() - m_tally.skipped;
  for (const auto& [id, fraction] : m_running) done += fraction;
  if (done <= 0.0) return -1.0;
  return elapsed * std::max(0.0, work - done) / done;
}

std::vector<std::string> ProgressReporter::block(int width, double elapsed) const {
  const int done = m_tally.done();
  const double left = seconds_left(elapsed);
  const int bar = 20;
  const int filled = m_tally.planned > 0 ? bar * done / m_tally.planned : bar;
  std::vector<std::string> lines;
  lines.push_back(fit(fmt::format("[{}{}] {}/{}  {} elapsed, ~{} left",
                                  std::string(static_cast<std::size_t>(filled), '#'),
                                  std::string(static_cast<std::size_t>(bar - filled), '-'), done,
                                  m_tally.planned, clock(elapsed),
                                  left >= 0.0 ? clock(left) : "--:--"),
                      width));
  lines.push_back(fit("  " + m_tally.summary(), width));
  const int id_width = std::max(8, width - 2 - 6);
  for (const auto& [id, fraction] : m_running) {
    if (lines.size() > max_running_lines + 1) {
      lines.push_back(fit(fmt::format("  ... and {} more running",
                                      m_running.size() - max_running_lines),
                          width));
      break;
    }
    lines.push_back(fit(fmt::format("  {:<{}} {:>4.0f}%", elide_middle(id, id_width), id_width,
                                    100.0 * fraction),
                        width));
  }
  return lines;
}

}  // namespace drape
