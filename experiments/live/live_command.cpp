#include "experiments/live/live_command.hpp"

#include <CLI/CLI.hpp>
#include <atomic>
#include <csignal>
#include <cstdlib>
#include <fmt/format.h>
#include <iostream>
#include <thread>

#include "core/scene/input_error.hpp"
#include "experiments/live/live_page.hpp"
#include "experiments/live/live_session.hpp"
#include "experiments/run/run_scene.hpp"

// Last: its system headers define macros that Eigen's templates (through the scene) trip over.
#include <httplib.h>

namespace drape {

namespace {

std::atomic<bool> g_interrupted{false};

extern "C" void on_interrupt(int) { g_interrupted = true; }

struct LiveOptions {
  std::string scene_file;
  std::string out_dir = "out/live";
  std::vector<std::string> overrides;
  int port = 0;
  bool open = false;
};

// GET /events: one server-sent event per new frame until the run ends or the client leaves.
void serve_events(httplib::Server& server, const LiveSession& session) {
  server.Get("/events", [&session](const httplib::Request&, httplib::Response& res) {
    res.set_header("Cache-Control", "no-cache");
    auto last = std::make_shared<long>(0);
    res.set_chunked_content_provider(
        "text/event-stream", [&session, last](std::size_t, httplib::DataSink& sink) {
          for (;;) {
            auto [number, frame] = session.frame();
            if (number != *last && frame) {
              *last = number;
              const std::string event = "data: " + *frame + "\n\n";
              return sink.write(event.data(), event.size());
            }
            if (session.finished()) {
              sink.done();
              return true;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(5));
          }
        });
  });
}

int live(const LiveOptions& o) {
  if (o.port < 1 || o.port > 65535)
    throw InputError("--port", "", fmt::format("{} is not a TCP port (1-65535)", o.port));
  const Scene scene = load_scene(o.scene_file, o.overrides);
  LiveSession session(scene, o.out_dir);

  httplib::Server server;
  server.Get("/", [](const httplib::Request&, httplib::Response& res) {
    res.set_content(live_page(), "text/html; charset=utf-8");
  });
  serve_events(server, session);
  server.Post("/key", [&session](const httplib::Request& req, httplib::Response& res) {
    if (req.body != "r" && req.body != "a" && req.body != "m") {
      res.status = 400;
      res.set_content("expected r, a or m\n", "text/plain");
      return;
    }
    session.key(req.body);
    res.set_content("ok\n", "text/plain");
  });
  // Loopback only: the page drives a simulation, nobody else on the network should.
  if (!server.bind_to_port("127.0.0.1", o.port))
    throw InputError("--port", "",
                     fmt::format("cannot listen on 127.0.0.1:{} (in use or not allowed)", o.port));
  std::thread server_thread([&server] { server.listen_after_bind(); });

  const std::string url = fmt::format("http://127.0.0.1:{}/", o.port);
  fmt::print("drapelab live {} -> {}: {} (Ctrl-C stops)\n", o.scene_file, o.out_dir, url);
  std::fflush(stdout);
  if (o.open) std::system(("xdg-open " + url + " >/dev/null 2>&1 &").c_str());

  g_interrupted = false;
  std::signal(SIGINT, on_interrupt);
  std::signal(SIGTERM, on_interrupt);
  std::string status;
  std::thread simulation_thread([&session, &status] { status = session.run(); });
  while (!session.finished()) {
    if (g_interrupted) session.stop();
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  simulation_thread.join();
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  server.stop();
  server_thread.join();
  fmt::print("drapelab live: {} ({}/summary.json)\n", status, o.out_dir);
  return status == "ok" || status == "stopped" ? exit_ok : exit_diverged;
}

}  // namespace

void add_live_command(CLI::App& app) {
  auto o = std::make_shared<LiveOptions>();
  CLI::App* cmd = app.add_subcommand(
      "live", "run a scene in wall-clock time and show it on http://127.0.0.1:PORT/");
  cmd->add_option("scene", o->scene_file, "scene JSON file")->required();
  cmd->add_option("--port", o->port, "TCP port on 127.0.0.1")->required();
  cmd->add_option("--out", o->out_dir, "output folder (default out/live)");
  cmd->add_option("--set", o->overrides, "override a scene value: key.path=value")->take_all();
  cmd->add_flag("--open", o->open, "open the page in the desktop's browser");
  cmd->callback([o] {
    int code = exit_ok;
    try {
      code = live(*o);
    } catch (const std::exception& e) {
      std::cerr << "drapelab: error: " << e.what() << "\n";
      throw CLI::RuntimeError(exit_input);
    }
    throw CLI::RuntimeError(code);
  });
}

}  // namespace drape
