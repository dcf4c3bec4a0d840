#include "experiments/live/sensor_bridge.hpp"

#include <arpa/inet.h>
#include <fmt/format.h>
#include <iostream>
#include <limits>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

namespace drape {

namespace {

constexpr int poll_ms = 100;                    // how often a waiting thread checks for stop
constexpr std::size_t max_line = 1 << 20;       // bytes; a longer line ends its connection

// Waits up to `ms` for input on fd; false on timeout.
bool readable(int fd, int ms = poll_ms) {
  pollfd p{fd, POLLIN, 0};
  return ::poll(&p, 1, ms) > 0;
}

}  // namespace

SensorBridge::SensorBridge(int port, FrameHandler on_frame)
    : m_port(port), m_on_frame(std::move(on_frame)) {
  if (port < 1 || port > 65535)
    throw InputError("--sensor-port", "", fmt::format("{} is not a TCP port (1-65535)", port));
  m_listen_fd = ::socket(AF_INET, SOCK_STREAM, 0);
  const int yes = 1;
  ::setsockopt(m_listen_fd, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<uint16_t>(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);  // a sensor on this machine only
  if (m_listen_fd < 0 ||
      ::bind(m_listen_fd, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0 ||
      ::listen(m_listen_fd, 4) != 0) {
    if (m_listen_fd >= 0) ::close(m_listen_fd);
    throw InputError("--sensor-port", "",
                     fmt::format("cannot listen on 127.0.0.1:{} (in use or not allowed)", port));
  }
  m_thread = std::thread([this] { serve(); });
}

SensorBridge::~SensorBridge() {
  m_stop = true;
  m_thread.join();
  ::close(m_listen_fd);
}

void SensorBridge::serve() {
  int connection = 0;
  while (!m_stop) {
    if (!readable(m_listen_fd)) continue;
    const int fd = ::accept(m_listen_fd, nullptr, nullptr);
    if (fd < 0) continue;
    read_connection(fd, fmt::format("sensor 127.0.0.1:{} connection {}", m_port, ++connection));
    ::close(fd);
  }
}

void SensorBridge::read_connection(int fd, const std::string& name) {
  std::string buffer;
  int number = 0;
  double previous_t = -std::numeric_limits<double>::infinity();
  char chunk[4096];
  bool said_waiting = false;
  while (!m_stop) {
    if (!readable(fd)) {
      // One connection is read at a time: a client that connects and sends nothing holds the
      // others back, which the terminal says, so that the wait is not silent.
      if (!said_waiting && readable(m_listen_fd, 0)) {
        said_waiting = true;
        std::cerr << fmt::format("drapelab live: {}: another sensor connection waits until this "
                                 "one closes (one is read at a time)\n", name);
      }
      continue;
    }
    const ssize_t n = ::recv(fd, chunk, sizeof chunk, 0);
    if (n < 0) return;  // the connection broke
    if (n == 0) {
      // Closed: a last line without its newline (a file piped in that does not end in one) is
      // still a line; it was dropped without a word.
      if (!buffer.empty()) line(buffer, name, ++number, previous_t);
      return;
    }
    buffer.append(chunk, static_cast<std::size_t>(n));
    std::size_t end;
    while ((end = buffer.find('\n')) != std::string::npos) {
      std::string text = buffer.substr(0, end);
      buffer.erase(0, end + 1);
      if (!text.empty() && text.back() == '\r') text.pop_back();
      line(text, name, ++number, previous_t);
    }
    if (buffer.size() > max_line) {
      ++m_malformed;
      std::cerr << fmt::format("drapelab live: {}: line {}: longer than {} bytes: connection closed\n",
                               name, number + 1, max_line);
      return;
    }
  }
}

void SensorBridge::line(const std::string& text, const std::string& name, int number,
                        double& previous_t) {
  const std::string where = fmt::format("line {}", number);
  if (text.find_first_not_of(" \t") == std::string::npos) return;  // blank, as in a file
  try {
    // A recording's header may open the stream (a file piped in as it is); it carries no frame.
    if (number == 1 && text.find("\"format\"") != std::string::npos) {
      read_drapelab_header_line(text, name, where);
      return;
    }
    const HandFrame frame = read_drapelab_frame_line(text, name, where);
    detail::check_time_order(previous_t, frame.t, name, where + ".t");
    previous_t = frame.t;
    m_on_frame(frame, name + ": " + where);  // throws InputError for a hand out of range
    ++m_frames;
  } catch (const InputError& e) {
    ++m_malformed;
    const std::string context = e.file().rfind(name, 0) == 0 ? "" : name + ": " + where + ": ";
    std::cerr << "drapelab live: " << context << e.what() << ": line ignored\n";
  }
}

}  // namespace drape
