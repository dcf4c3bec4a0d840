#pragma once
// The live mode's sensor bridge (docs/live.md, "Sensor bridge"): a TCP socket on 127.0.0.1 that
// reads hand frames as JSON Lines, each line as a line of a drapelab recording (docs/input.md).
#include <atomic>
#include <functional>
#include <string>
#include <thread>

#include "core/input/recording.hpp"

namespace drape {

/// Listens on 127.0.0.1:port from construction until destruction, one connection at a time.
/// Every valid frame goes to `on_frame` with its connection and line (from the bridge's thread). A malformed line (bad JSON,
/// an unknown field, a NaN, a time not later than the connection's previous frame) is reported
/// on stderr with its connection and line and ignored; the connection stays open.
class SensorBridge {
 public:
  /// Throws InputError naming `--sensor-port` when it cannot listen there.
  using FrameHandler = std::function<void(const HandFrame&, const std::string& where)>;
  SensorBridge(int port, FrameHandler on_frame);
  ~SensorBridge();
  SensorBridge(const SensorBridge&) = delete;
  SensorBridge& operator=(const SensorBridge&) = delete;

  long frames() const { return m_frames; }
  long malformed() const { return m_malformed; }

 private:
  void serve();
  void read_connection(int fd, const std::string& name);
  void line(const std::string& text, const std::string& name, int number, double& previous_t);

  int m_port;
  int m_listen_fd = -1;
  FrameHandler m_on_frame;
  std::atomic<bool> m_stop{false};
  std::atomic<long> m_frames{0};
  std::atomic<long> m_malformed{0};
  std::thread m_thread;
};

}  // namespace drape
