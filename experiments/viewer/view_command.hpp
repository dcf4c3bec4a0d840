#pragma once
// The `view` subcommand of drapelab: runs in 3-D in one HTML page (docs/viewer.md).
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace drape {

/// Writes the viewer page of the run folders to out_file. Throws InputError naming the folder
/// or the file when a folder is not a run or a file is malformed.
void view_command(const std::vector<std::string>& run_dirs, const std::string& out_file);

/// Adds `view RUN_DIR... --out page.html` to the app; it runs when parsed and ends the parse
/// with CLI::RuntimeError carrying the exit status (0 written, 2 invalid input).
void add_view_command(CLI::App& app);

}  // namespace drape
