#pragma once
// The `live` subcommand of drapelab: a scene run in wall-clock time and shown as it is computed
// on a page served on 127.0.0.1 (docs/live.md).
namespace CLI {
class App;
}

namespace drape {

/// Adds `live SCENE --port P [--out DIR] [--open] [--set k=v]...` to the app; it runs when parsed
/// and ends the parse with CLI::RuntimeError carrying the exit status (0 done or stopped,
/// 2 invalid input, a bad port or a port in use).
void add_live_command(CLI::App& app);

}  // namespace drape
