#include "experiments/viewer/view_command.hpp"

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "core/io/input_error.hpp"
#include "core/io/json_text.hpp"
#include "core/io/output_error.hpp"
#include "experiments/output/live_run_files.hpp"
#include "experiments/output/run_folder.hpp"
#include "experiments/runner/run_scene.hpp"
#include "experiments/sweep/experiment_folder.hpp"
#include "experiments/viewer/viewer_page.hpp"

namespace drape {

namespace {

namespace fs = std::filesystem;

bool contains(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

// Throws InputError naming --out when the page would replace a file or folder of a run it
// shows, or of that run's experiment (`view RUN --out RUN/summary.json` replaced the summary),
// or cannot be written; makes the page's folder.
void check_out(const fs::path& out, const std::vector<std::string>& run_dirs) {
  if (const auto reason = unwritable_file_reason(out.string()))
    throw InputError(out.empty() ? "--out" : out.string(), out.empty() ? "" : "--out", *reason);
  std::error_code ec;
  if (fs::is_directory(out, ec))
    throw InputError(out.string(), "--out", "is a folder: name the HTML file to write");
  const fs::path target = fs::weakly_canonical(fs::absolute(out), ec);
  const std::string name = target.filename().string();
  for (const std::string& dir : run_dirs) {
    const fs::path run = fs::weakly_canonical(fs::absolute(dir), ec);
    if (target.parent_path() == run &&
        (contains(run_file_names(), name) || contains(experiment_run_file_names(), name) ||
         contains(live_run_file_names(), name)))
      throw InputError(out.string(), "--out", "is the run's own " + name + " (in " + dir +
                                                  "): name another HTML file");
    const fs::path experiment = run.parent_path().parent_path();
    if (run.parent_path().filename() == "runs" && target.parent_path() == experiment &&
        fs::exists(experiment / "experiment.json", ec) && contains(experiment_file_names(), name))
      throw InputError(out.string(), "--out", "is the experiment's own " + name + " (in " +
                                                  experiment.string() +
                                                  "): name another HTML file");
  }
  // A folder that cannot be made or a file that cannot be written is named now (exit 2), not
  // found by the write at the end (exit 4).
  if (out.has_parent_path()) {
    fs::create_directories(out.parent_path(), ec);
    if (ec) throw InputError(out.string(), "--out", "its folder cannot be made: " + ec.message());
  }
  if (const auto reason = open_for_writing_reason(out.string()))
    throw InputError(out.string(), "--out", *reason);
}

}  // namespace

void view_command(const std::vector<std::string>& run_dirs, const std::string& out_file) {
  std::vector<ViewerRun> runs;
  for (const std::string& dir : run_dirs) runs.push_back(read_viewer_run(dir));
  // Folders of the same name (out/a/run, out/b/run) are told apart by their parent's name.
  std::vector<std::string> names;
  for (const ViewerRun& run : runs) names.push_back(run.name);
  for (size_t i = 0; i < runs.size(); ++i)
    if (std::count(names.begin(), names.end(), names[i]) > 1) {
      std::filesystem::path dir = std::filesystem::absolute(run_dirs[i]).lexically_normal();
      if (dir.filename().empty()) dir = dir.parent_path();  // a trailing slash
      runs[i].name = dir.parent_path().filename().string() + "/" + names[i];
    }
  for (size_t i = 0; i < runs.size(); ++i)
    if (!is_utf8(runs[i].name))  // the page names each run by its folder, in a JSON string
      throw InputError(run_dirs[i], "", "the folder's name is not valid UTF-8, which the page "
                                        "needs to name the run: rename the folder");
  const std::filesystem::path out(out_file);
  check_out(out, run_dirs);
  const std::string page = viewer_page(runs);
  errno = 0;
  std::ofstream file(out, std::ios::binary);
  if (!(file << page) || !file.flush()) fail_write(out_file);  // a cut page would load as an empty viewer
  size_t frames = 0;
  for (const ViewerRun& run : runs) frames += run.frames.size();
  std::cout << fmt::format("drapelab view: {} ({} run{}, {} frames, {:.1f} MB)\n", out_file,
                           runs.size(), runs.size() == 1 ? "" : "s", frames, page.size() / 1e6);
}

void add_view_command(CLI::App& app) {
  // The options live as long as the app: the callback runs inside app.parse().
  auto dirs = std::make_shared<std::vector<std::string>>();
  auto out = std::make_shared<std::string>();
  CLI::App* view = app.add_subcommand(
      "view", "write one self-contained HTML page that plays runs in 3-D, side by side");
  view->add_option("runs", *dirs, "run folders (drapelab run --out), shown side by side")
      ->required();
  view->add_option("--out", *out, "HTML file to write")->required();
  // Ends the parse: drapelab's main turns the status of CLI::RuntimeError into its exit status.
  view->callback([dirs, out] {
    try {
      view_command(*dirs, *out);
    } catch (const OutputError& e) {
      std::cerr << "drapelab: error: " << e.what() << "\n";
      throw CLI::RuntimeError(exit_output);
    } catch (const std::exception& e) {
      std::cerr << "drapelab: error: " << e.what() << "\n";
      throw CLI::RuntimeError(exit_input);
    }
    throw CLI::RuntimeError(exit_ok);
  });
}

}  // namespace drape
