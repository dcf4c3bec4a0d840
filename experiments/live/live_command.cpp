#include "experiments/live/live_command.hpp"

#include <CLI/CLI.hpp>
#include <atomic>
#include <csignal>
#include <cstdlib>
#include <fmt/format.h>
#include <iostream>
#include <optional>
#include <thread>

#include "core/parallel/parallel_for.hpp"
#include "core/io/input_error.hpp"
#include "core/io/output_error.hpp"
#include "core/io/json_reader.hpp"
#include "core/io/json_text.hpp"
#include "experiments/options/decimal_integer.hpp"
#include "experiments/options/threads_option.hpp"
#include "experiments/live/live_page.hpp"
#include "experiments/live/live_session.hpp"
#include "experiments/live/sensor_bridge.hpp"
#include "experiments/output/run_folder.hpp"
#include "experiments/runner/run_scene.hpp"

// Last: it includes httplib.h, whose system headers define macros that Eigen's templates
// (through the scene) trip over.
#include "experiments/live/connection_threads.hpp"

namespace drape {

namespace {

std::atomic<bool> g_interrupted{false};

extern "C" void on_interrupt(int) { g_interrupted = true; }

struct LiveOptions {
  std::string scene_file;
  std::string out_dir = "out/live";
  std::vector<std::string> overrides;
  int port = 0;
  std::optional<int> sensor_port;  ///< none: no sensor bridge
  bool live_hands = false;
  bool open = false;
  bool overwrite = false;
  int threads = 0;  ///< 0: all cores
};

void check_port(const std::string& option, int port) {
  if (port < 1 || port > 65535)
    throw InputError(option, "", fmt::format("{} is not a TCP port (1-65535)", port));
}

// Everything the command line alone can refuse, before the scene is read or a file written, as
// `drapelab run` checks its --out.
void check_options(const LiveOptions& o) {
  check_port("--port", o.port);
  if (o.sensor_port) {
    check_port("--sensor-port", *o.sensor_port);
    if (*o.sensor_port == o.port)
      throw InputError("--port, --sensor-port", "",
                       fmt::format("both are {}: the page and the sensor bridge need a port each",
                                   o.port));
  }
  check_run_folder(o.out_dir, o.overwrite);
  check_run_folder_not_experiment(o.out_dir);
}

// Only this server's own page, and clients that name it, may drive the run (docs/live.md,
// "Protocol"): a page of any other site open in the same browser could POST a key or a hand
// (a cross-origin text/plain POST needs no preflight), and a Host that is not this server is
// what a DNS-rebinding page sends. Both are refused with 403.
void refuse_other_origins(httplib::Server& server, int port) {
  const std::string ours[] = {fmt::format("127.0.0.1:{}", port), fmt::format("localhost:{}", port)};
  const auto is_ours = [ours](const std::string& host) {
    return host == ours[0] || host == ours[1];
  };
  server.set_pre_routing_handler([is_ours](const httplib::Request& req, httplib::Response& res) {
    const std::string host = req.get_header_value("Host");
    const std::string origin = req.get_header_value("Origin");
    const std::string scheme = "http://";
    const bool origin_ours = !req.has_header("Origin") ||
                             (origin.rfind(scheme, 0) == 0 && is_ours(origin.substr(scheme.size())));
    if (is_ours(host) && origin_ours) return httplib::Server::HandlerResponse::Unhandled;
    res.status = 403;
    res.set_content(is_ours(host) ? "another site's page may not drive this run (Origin " + origin + ")\n"
                                  : "not this server (Host " + host + ")\n",
                    "text/plain");
    return httplib::Server::HandlerResponse::Handled;
  });
}

// Pages that may watch at once (docs/live.md, "Many connections"): each stream costs a thread
// and a copy of every frame, 30 a second, on the cores the simulation runs on; a browser opens
// at most 6 connections to one server, so this is more than anyone's tabs.
constexpr int max_event_streams = 16;
// Connections served at once, each on its own thread (ConnectionThreads); beyond, a connection
// waits for one to end. Far beyond the streams, so control requests never wait behind them.
constexpr std::size_t max_connection_threads = 512;

// An open event stream, counted while it lives: httplib drops the stream's provider, and so this,
// however the stream ended (the run's end, the client gone, a write that timed out).
class StreamSlot {
 public:
  explicit StreamSlot(std::shared_ptr<std::atomic<int>> open) : m_open(std::move(open)) {}
  StreamSlot(const StreamSlot&) = delete;
  StreamSlot& operator=(const StreamSlot&) = delete;
  ~StreamSlot() { --*m_open; }

 private:
  std::shared_ptr<std::atomic<int>> m_open;
};

// GET /events: one server-sent event per new frame until the run ends or the client leaves;
// 503 with the reason beyond max_event_streams open at once. Returns the count of open streams.
std::shared_ptr<const std::atomic<int>> serve_events(httplib::Server& server,
                                                     const LiveSession& session) {
  auto open = std::make_shared<std::atomic<int>>(0);
  server.Get("/events", [&session, open](const httplib::Request&, httplib::Response& res) {
    if (++*open > max_event_streams) {
      --*open;
      res.status = 503;
      res.set_content(fmt::format("too many event streams: at most {} pages may watch this run "
                                  "at once; close one and reload\n",
                                  max_event_streams),
                      "text/plain");
      return;
    }
    auto slot = std::make_shared<StreamSlot>(open);
    res.set_header("Cache-Control", "no-cache");
    auto last = std::make_shared<long>(0);
    res.set_chunked_content_provider(
        "text/event-stream", [&session, last, slot](std::size_t, httplib::DataSink& sink) {
          for (;;) {
            // Read before the frame: the run publishes its last frame before it finishes, so a
            // finished run's frame read after is the last one, which the page must get.
            const bool finished = session.finished();
            auto [number, frame] = session.frame();
            if (number != *last && frame) {
              *last = number;
              const std::string event = "data: " + *frame + "\n\n";
              return sink.write(event.data(), event.size());
            }
            if (finished) {
              sink.done();
              return true;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(5));
          }
        });
  });
  return open;
}

// POST /hand: {"x": .., "y": .., "z": ..} in the scene frame, optionally "hand": "left" or
// "right" (default), or {"hand": .., "tracked": false} to take the hand away.
void serve_hand(httplib::Server& server, LiveSession& session) {
  server.Post("/hand", [&session](const httplib::Request& req, httplib::Response& res) {
    res.status = 400;
    if (!session.live_hands()) {
      res.status = 409;
      res.set_content("the hands replay the scene's recording; start drapelab live with "
                      "--live-hands to drive them\n", "text/plain");
      return;
    }
    try {
      const nlohmann::json body = parse_json_text(req.body, "POST /hand");
      if (!body.is_object()) throw InputError("POST /hand", "", "expected a JSON object");
      JsonReader reader(body, "POST /hand", "");
      const std::string name = reader.string("hand", "right");
      if (name != "left" && name != "right")
        throw reader.error("hand", "expected \"left\" or \"right\"");
      std::optional<HandSample> sample;
      if (reader.boolean("tracked", true))
        sample = HandSample{Vec3(reader.number("x"), reader.number("y"), reader.number("z")), false};
      reader.finish();
      session.hand(name == "left" ? Hand::Left : Hand::Right, sample, "POST /hand");
      res.status = 200;
      res.set_content("ok\n", "text/plain");
    } catch (const InputError& e) {
      res.set_content(std::string(e.what()) + "\n", "text/plain");
    }
  });
}

// Binds 127.0.0.1:port with the system's longest queue of connections not yet accepted. Debian's
// httplib listens with a queue of 5 (CPPHTTPLIB_LISTEN_BACKLOG, compiled into the library): a
// burst of connections beyond it (a page's requests, many clients at once) has its SYNs
// dropped and retried a second or more later (200 connections take 15 s to open). Linux takes
// a second listen() on a listening socket as a new queue length (listen(2)).
void listen_on_loopback(httplib::Server& server, int port) {
  socket_t bound = INVALID_SOCKET;
  server.set_socket_options([&bound](socket_t sock) {
    httplib::default_socket_options(sock);
    bound = sock;
  });
  const bool listening = server.bind_to_port("127.0.0.1", port) && ::listen(bound, SOMAXCONN) == 0;
  server.set_socket_options(httplib::default_socket_options);  // `bound` goes out of scope
  if (!listening)
    throw InputError("--port", "",
                     fmt::format("cannot listen on 127.0.0.1:{} (in use or not allowed)", port));
}

// The exit status of a session that ended with `status` (LiveSession::run).
int exit_status_of(const std::string& status) {
  return status == "ok" || status == "stopped" ? exit_ok : exit_diverged;
}

// Prints why the command failed and returns its exit status: 4 for a failed write, 2 for bad
// input (anything else the setup refuses).
int report_failure(const std::exception_ptr& failure) {
  try {
    std::rethrow_exception(failure);
  } catch (const OutputError& e) {
    std::cerr << "drapelab: error: " << e.what() << "\n";
    return exit_output;
  } catch (const std::exception& e) {
    std::cerr << "drapelab: error: " << e.what() << "\n";
    return exit_input;
  }
}

int live(const LiveOptions& o) {
  check_options(o);
  use_threads(o.threads, available_processors());
  // Both ports are taken before the session clears --out: a port in use must not cost the
  // folder's earlier run. The session outlives the bridge that feeds it (declared first);
  // frames that arrive before it exists, before the banner, are dropped.
  std::unique_ptr<LiveSession> owned_session;
  std::atomic<LiveSession*> frames_to{nullptr};
  httplib::Server server;
  // Loopback only: the page drives a simulation, nobody else on the network should.
  listen_on_loopback(server, o.port);
  std::unique_ptr<SensorBridge> sensor;
  if (o.sensor_port)
    sensor = std::make_unique<SensorBridge>(
        *o.sensor_port, [&frames_to](const HandFrame& frame, const std::string& where) {
          if (LiveSession* session = frames_to.load()) session->sensor_frame(frame, where);
        });
  owned_session = with_command_line_overrides(
      o.scene_file, o.overrides, [&o](const Scene& scene) {
        return std::make_unique<LiveSession>(scene, o.out_dir,
                                             o.live_hands || o.sensor_port.has_value());
      });
  LiveSession& session = *owned_session;
  frames_to = &session;
  // A request body is a hand position or a key: 1 MiB is far beyond either, and a client
  // sending gigabytes must get 413, not the server's memory.
  server.set_payload_max_length(1 << 20);
  refuse_other_origins(server, o.port);
  server.new_task_queue = [] { return new ConnectionThreads(max_connection_threads); };
  // One request per connection. httplib waits for a connection's next request by polling its
  // socket every 10 ms for 5 s (keep_alive in httplib.h), and a handler cannot end its own
  // connection: 185 streams refused with 503 would keep their threads polling, 0.3 s more CPU
  // a second on the cores the simulation needs. A new loopback connection costs far less.
  server.set_keep_alive_max_count(1);
  const std::string page = live_page(session.scene_json());
  server.Get("/", [&page](const httplib::Request&, httplib::Response& res) {
    res.set_content(page, "text/html; charset=utf-8");
  });
  const auto open_streams = serve_events(server, session);
  server.Get("/event-log", [&session](const httplib::Request&, httplib::Response& res) {
    res.set_header("Cache-Control", "no-cache");
    res.set_content(session.event_log().dump(), "application/json");
  });
  serve_hand(server, session);
  server.Post("/key", [&session](const httplib::Request& req, httplib::Response& res) {
    if (req.body != "r" && req.body != "a" && req.body != "m") {
      res.status = 400;
      res.set_content("expected r, a or m\n", "text/plain");
      return;
    }
    session.key(req.body);
    res.set_content("ok\n", "text/plain");
  });
  std::atomic<bool> listened{false};
  std::thread server_thread([&server, &listened] {
    server.listen_after_bind();
    listened = true;
  });
  // httplib's stop() does nothing before the listening loop has started, which then never
  // ends: a Ctrl-C right after the banner hung in server_thread.join(). The banner waits.
  while (!server.is_running() && !listened)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));

  // Ctrl-C stops the session from the moment the banner says so: a client that waits for the
  // banner and then interrupts must not meet the default handler (which kills the process).
  g_interrupted = false;
  std::signal(SIGINT, on_interrupt);
  std::signal(SIGTERM, on_interrupt);
  const std::string url = fmt::format("http://127.0.0.1:{}/", o.port);
  fmt::print("drapelab live {} -> {}: {} (Ctrl-C stops){}\n", o.scene_file, o.out_dir, url,
             sensor ? fmt::format("; sensor bridge on 127.0.0.1:{}", *o.sensor_port) : "");
  std::fflush(stdout);
  if (o.open) std::system(("xdg-open " + url + " >/dev/null 2>&1 &").c_str());

  std::string status;
  std::exception_ptr failure;  // a failed write (exit 4) ends the run, not the process
  std::thread simulation_thread([&session, &status, &failure] {
    try {
      status = session.run();
    } catch (...) {
      failure = std::current_exception();
    }
  });
  while (!session.finished()) {
    if (g_interrupted) session.stop();
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  simulation_thread.join();
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  // The streams end with the run, within a frame or so; httplib's chunked writer stops at
  // stop() without the closing chunk, and a page still reading the last frame (a busy machine,
  // a slow browser) reported ERR_INCOMPLETE_CHUNKED_ENCODING. A client that does not read
  // holds its stream up to httplib's 5 s write timeout: the wait has a bound of its own.
  const auto streams_deadline = std::chrono::steady_clock::now() + std::chrono::seconds(2);
  while (*open_streams > 0 && std::chrono::steady_clock::now() < streams_deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  server.stop();
  // A client that keeps a request open, sending a byte now and then, holds its worker, and
  // httplib's stop() waits for every worker: the run's files are written, so after 5 s the
  // command ends without it.
  const auto stop_deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (!listened && std::chrono::steady_clock::now() < stop_deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  if (!listened) {
    fmt::print(stderr, "drapelab live: a client still holds a request open; ending without it\n");
    const int code = failure ? report_failure(failure) : exit_status_of(status);
    std::fflush(stdout);
    std::fflush(stderr);
    std::_Exit(code);
  }
  server_thread.join();
  if (failure) std::rethrow_exception(failure);
  if (sensor)
    fmt::print("drapelab live: sensor bridge: {} frames, {} malformed lines ignored\n",
               sensor->frames(), sensor->malformed());
  fmt::print("drapelab live: {} ({}/summary.json)\n", status, o.out_dir);
  return exit_status_of(status);
}

}  // namespace

void add_live_command(CLI::App& app) {
  auto o = std::make_shared<LiveOptions>();
  CLI::App* cmd = app.add_subcommand(
      "live", "run a scene in wall-clock time and show it on http://127.0.0.1:PORT/");
  cmd->add_option("scene", o->scene_file, "scene JSON file")->required();
  cmd->add_option("--port", o->port, "TCP port on 127.0.0.1")->required()->transform(decimal_integer());
  cmd->add_option("--out", o->out_dir, "output folder (default out/live)");
  cmd->add_flag("--overwrite", o->overwrite, "replace the run files of an earlier run in --out");
  cmd->add_option("--set", o->overrides, "override a scene value: key.path=value")->take_all();
  cmd->add_option("--sensor-port", o->sensor_port,
                  "read hand frames (recording JSON Lines) on 127.0.0.1:PORT; implies --live-hands")
      ->transform(decimal_integer());
  cmd->add_flag("--live-hands", o->live_hands,
                "the page's pointer (POST /hand) and the sensor bridge drive the hands instead "
                "of the scene's recording (always so for a scene without recorded hands)");
  cmd->add_flag("--open", o->open, "open the page in the desktop's browser");
  add_threads_option(*cmd, o->threads, "all cores");
  cmd->footer(
      "Examples (docs/live.md):\n"
      "  drapelab live experiments/scenes/fig6_map.json --port 8080       # keys r a m in the page\n"
      "  drapelab live experiments/scenes/fig2_hold.json --port 8080 --live-hands   # h: pointer hand\n"
      "  drapelab live experiments/scenes/fig2_hold.json --port 8080 --sensor-port 9000\n"
      "  drapelab run out/live/scene.json --out out/replay                # replay a live run");
  cmd->callback([o] {
    int code = exit_ok;
    try {
      code = live(*o);
    } catch (const std::exception&) {
      code = report_failure(std::current_exception());
    }
    throw CLI::RuntimeError(code);
  });
}

}  // namespace drape
