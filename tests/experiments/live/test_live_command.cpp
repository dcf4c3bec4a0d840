// `drapelab live`: its options are refused before anything is served or written. Every case
// sets a 0.05 s duration, so that a session that did start ends within a second.
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <filesystem>

#include "tests/support/drapelab_process.hpp"

namespace {

namespace fs = std::filesystem;
using drape::testing::read_text;
using drape::testing::run_drapelab;

// A port nothing listens on now (the system's choice for a socket bound to port 0).
int free_port() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t size = sizeof address;
  ::bind(fd, reinterpret_cast<sockaddr*>(&address), size);
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&address), &size);
  ::close(fd);
  return ntohs(address.sin_port);
}

std::string live(const fs::path& out, const std::string& ports) {
  return "live " + std::string(DRAPE_SOURCE_DIR) + "/experiments/scenes/fig6_map.json " + ports +
         " --out " + out.string() + " --set duration=0.05";
}

fs::path fresh(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("live_command_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(LiveCommand, RefusesARunsFolderAsRunDoesAndReplacesItWithOverwrite) {
  const fs::path run = fresh("run");
  std::ofstream(run / "summary.json") << R"({"status": "ok"})";
  std::ofstream(run / "energy.csv") << "t,total\n0,1\n";
  const auto refused = run_drapelab(live(run, "--port " + std::to_string(free_port())));
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_EQ(refused.err, "drapelab: error: " + run.string() +
                             ": --out: holds another run's files (summary.json, energy.csv); pass "
                             "--overwrite to replace them, or choose another folder\n");
  EXPECT_EQ(read_text(run / "summary.json"), R"({"status": "ok"})");

  const auto replaced =
      run_drapelab(live(run, "--port " + std::to_string(free_port())) + " --overwrite");
  EXPECT_EQ(replaced.exit_code, 0) << replaced.err;
  EXPECT_NE(read_text(run / "summary.json").find("\"status\": \"ok\""), std::string::npos);
  EXPECT_NE(read_text(run / "summary.json").find("\"live\""), std::string::npos);
}

// A socket listening on a port the system chose, held until destruction.
struct BusyPort {
  int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  int port = 0;
  BusyPort() {
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t size = sizeof address;
    ::bind(fd, reinterpret_cast<sockaddr*>(&address), size);
    ::listen(fd, 1);
    ::getsockname(fd, reinterpret_cast<sockaddr*>(&address), &size);
    port = ntohs(address.sin_port);
  }
  ~BusyPort() { ::close(fd); }
};

TEST(LiveCommand, APortInUseLeavesTheFoldersEarlierRun) {
  // Both ports are taken before --overwrite clears the folder: the earlier run stays whole.
  const fs::path run = fresh("busy");
  std::ofstream(run / "summary.json") << R"({"status": "ok"})";
  const BusyPort busy;
  const std::string busy_port = std::to_string(busy.port);
  for (const std::string& ports :
       {"--port " + busy_port, "--port " + std::to_string(free_port()) + " --sensor-port " + busy_port}) {
    const auto r = run_drapelab(live(run, ports) + " --overwrite");
    EXPECT_EQ(r.exit_code, 2) << ports;
    EXPECT_NE(r.err.find("cannot listen on 127.0.0.1:" + busy_port), std::string::npos) << r.err;
    EXPECT_EQ(read_text(run / "summary.json"), R"({"status": "ok"})") << ports;
  }
}

TEST(LiveCommand, RefusesAFileAsOutAndBadOrSharedPortsNamingTheOptions) {
  const fs::path dir = fresh("options");
  std::ofstream(dir / "a_file") << "x";
  auto expect_error = [](const std::string& args, const std::string& message) {
    const auto r = run_drapelab(args);
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_EQ(r.err, "drapelab: error: " + message + "\n") << args;
  };
  expect_error(live(dir / "a_file", "--port 8080"),
               (dir / "a_file").string() + ": --out: exists and is not a folder");
  expect_error(live(dir / "out", "--port 8080 --sensor-port 0"),
               "--sensor-port: 0 is not a TCP port (1-65535)");
  expect_error(live(dir / "out", "--port 8080 --sensor-port 8080"),
               "--port, --sensor-port: both are 8080: the page and the sensor bridge need a port "
               "each");
  // Ports are decimal: CLI11 alone read 0x50 as port 80 and 010 as port 8.
  expect_error(live(dir / "out", "--port 8080 --sensor-port 08080"),
               "--port, --sensor-port: both are 8080: the page and the sensor bridge need a port "
               "each");
  for (const std::string ports : {"--port 0x50", "--port 8080 --sensor-port 0x50"}) {
    const auto r = run_drapelab(live(dir / "out", ports));
    EXPECT_EQ(r.exit_code, 2) << ports;
    EXPECT_NE(r.err.find("port: expected a decimal integer, got '0x50'"), std::string::npos)
        << r.err;
  }
  EXPECT_FALSE(fs::exists(dir / "out"));
}

}  // namespace
