#include "experiments/viewer/view_command.hpp"

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>

#include "core/scene/input_error.hpp"
#include "experiments/run/run_scene.hpp"
#include "experiments/viewer/viewer_page.hpp"

namespace drape {

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
  const std::string page = viewer_page(runs);
  const std::filesystem::path out(out_file);
  if (out.has_parent_path()) std::filesystem::create_directories(out.parent_path());
  std::ofstream file(out, std::ios::binary);
  if (!(file << page) || !file.flush()) throw InputError(out_file, "", "cannot write the page");
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
    } catch (const std::exception& e) {
      std::cerr << "drapelab: error: " << e.what() << "\n";
      throw CLI::RuntimeError(exit_input);
    }
    throw CLI::RuntimeError(exit_ok);
  });
}

}  // namespace drape
