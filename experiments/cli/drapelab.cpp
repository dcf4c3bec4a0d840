// drapelab: the command line of the testbed (docs/model.md section 9).
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <csignal>
#include <iostream>
#include <optional>

#include <unistd.h>

#include "core/parallel/parallel_for.hpp"
#include "core/io/input_error.hpp"
#include "core/input/recording.hpp"
#include "core/scene/scene.hpp"
#include "experiments/cli/convert_command.hpp"
#include "experiments/cli/did_you_mean.hpp"
#include "experiments/cli/experiment_cli.hpp"
#include "experiments/catalogue/fabrics_command.hpp"
#include "experiments/cli/integrators_command.hpp"
#include "experiments/cli/run_stats.hpp"
#include "experiments/options/threads_option.hpp"
#include "experiments/output/provenance.hpp"
#include "experiments/output/run_files.hpp"
#include "experiments/cli/run_progress_display.hpp"
#include "experiments/output/run_folder.hpp"
#include "experiments/runner/run_scene.hpp"
#include "experiments/viewer/view_command.hpp"
#include "experiments/live/live_command.hpp"

namespace {

int run_command(const std::string& scene_file, const std::string& out_dir,
                const std::vector<std::string>& overrides, bool quiet, bool overwrite,
                int threads) {
  drape::use_threads(threads, drape::available_processors());
  drape::check_run_folder(out_dir, overwrite);  // before anything is read or built
  drape::check_run_folder_not_experiment(out_dir);
  // Progress only where a person watches (a terminal, not --quiet), from when the scene is read.
  std::optional<drape::RunProgressDisplay> progress;
  const drape::RunOutcome outcome = drape::with_command_line_overrides(
      scene_file, overrides, [&](const drape::Scene& scene) {
        if (!quiet && ::isatty(2) != 0) progress.emplace(scene_file, std::cerr);
        return drape::run_scene(scene, out_dir, progress ? &*progress : nullptr);
      });
  if (progress) progress->finish(outcome.status);
  if (outcome.status != "ok")
    std::cerr << fmt::format("drapelab: {}: {} at t = {:.6g} s: {}\n", scene_file, outcome.status,
                             outcome.summary.value("time", 0.0), outcome.reason);
  if (!quiet)
    fmt::print("drapelab run {} -> {}\n{}", scene_file, out_dir,
               drape::format_run_stats(outcome.summary));
  return outcome.exit_code;
}

// What goes to standard output (the integrators' list, a table, --version, --list) is the
// command's output: a write that failed there (a full disk, /dev/full) is exit 4 as for a file,
// not exit 0 with an empty or cut result that a script would take (docs/model.md section 9).
int with_standard_output_checked(int code) {
  std::cout.flush();
  const bool failed = !std::cout || std::fflush(stdout) != 0 || std::ferror(stdout);
  if (!failed) return code;
  std::cerr << "drapelab: error: cannot write to standard output\n";
  return code == 0 || code == drape::exit_failure ? drape::exit_output : code;
}

}  // namespace

// The command line, parsed and run; its exit status (main checks standard output after it).
static int run_drapelab(int argc, char** argv) {
  // Past a file size limit (ulimit -f) the kernel's default is to kill the process; ignored, the
  // write fails with EFBIG instead and the run stops as a failed write, exit 4 (docs/outputs.md).
  std::signal(SIGXFSZ, SIG_IGN);
  CLI::App app{"drapelab: a numerical testbed for virtual draping"};
  app.require_subcommand(1);
  app.set_version_flag("--version", [] { return drape::version_text(); },
                       "print version, git commit, build type, SUNDIALS and machine, then exit");

  std::string scene_file, out_dir;
  std::vector<std::string> overrides;
  auto* run = app.add_subcommand("run", "run one scene and write summary.json, energy.csv, state.csv");
  run->add_option("scene", scene_file, "scene JSON file")->required();
  run->add_option("--out", out_dir, "output folder")->required();
  run->add_option("--set", overrides, "override a scene value: key.path=value (JSON or string)")
      ->take_all();
  bool quiet = false;
  run->add_flag("--quiet,-q", quiet, "print nothing on success (the stats block is summary.json)");
  run->footer(
      "Examples:\n"
      "  drapelab run experiments/scenes/drape_dress_form.json --out out/drape\n"
      "  drapelab run experiments/scenes/fig2_hold.json --out out/fig2 \\\n"
      "      --set duration=1 --set output.vtk_interval=0.04   # ParaView: out/fig2/frames/\n"
      "  drapelab run experiments/scenes/combination4_hold_release_attach.json --out out/c4 \\\n"
      "      --set integrator.name=arkode-dirk --set integrator.dt=0.001");
  bool overwrite = false;
  run->add_flag("--overwrite", overwrite, "replace the run files of an earlier run in --out");
  int run_threads = 0;
  drape::add_threads_option(*run, run_threads, "all cores");

  std::string dirk_table;
  auto* integrators =
      app.add_subcommand("integrators", "list integrators and ARKODE tables with their orders");
  auto* table_option = integrators->add_option("--table", dirk_table,
                          "print this arkode-dirk table's coefficients as the inline JSON "
                          "tableau integrator.table accepts");
  std::string stability_scene;
  std::vector<std::string> stability_overrides;
  auto* stability_option = integrators->add_option(
      "--stability", stability_scene,
      "print the explicit steps' stability limit on this scene's cloth at its start: the fastest "
      "mode's frequency and damping rate (docs/model.md, \"Stability limit\")");
  // An option that would be ignored is refused instead (exit 2), as CLI11 says which.
  integrators
      ->add_option("--set", stability_overrides,
                   "with --stability: override a scene value (key.path=value)")
      ->needs(stability_option);
  stability_option->excludes(table_option);
  bool integrators_json = false;
  integrators
      ->add_flag("--json", integrators_json,
                 "print each integrator's declaration (family, order, keys with defaults and "
                 "ranges) as JSON")
      ->excludes(table_option)
      ->excludes(stability_option);
  integrators->footer(
      "Examples:\n  drapelab integrators\n  drapelab integrators --json\n"
      "  drapelab integrators --table ARKODE_KVAERNO_4_2_3 > kvaerno.json\n"
      "  drapelab integrators --stability experiments/scenes/drape_dress_form.json");
  bool fabrics_json = false;
  auto* fabrics = app.add_subcommand("fabrics", "list fabric presets and their published sources");
  fabrics->add_flag("--json", fabrics_json, "print a JSON list");
  fabrics->footer("Examples:\n  drapelab fabrics\n  drapelab fabrics --json");

  std::string convert_in, convert_out;
  auto* convert = app.add_subcommand(
      "convert", "convert a hand recording (Kinect v2 CSV, NTU .skeleton, drapelab) to drapelab JSON Lines");
  convert->add_option("in", convert_in, "recording to read")->required();
  convert->add_option("out", convert_out, "drapelab recording (.jsonl) to write")->required();
  convert->footer(
      "Prints the frames, duration and dropped frames of the recording.\n"
      "Example:\n"
      "  drapelab convert experiments/recordings/kinect-v2/Ges03_drawlines.csv out/ges03.jsonl");

  const drape::ExperimentCommands experiment_commands(app);
  drape::add_view_command(app);  // runs inside app.parse (docs/viewer.md)
  drape::add_live_command(app);  // runs inside app.parse (docs/viewer.md, Live mode)

  // CLI11 prints the version as soon as it meets the flag and ignores everything else on the
  // line; an argument that would be ignored is refused instead, as elsewhere.
  if (argc > 2 && std::find(argv + 1, argv + argc, std::string("--version")) != argv + argc) {
    std::cerr << "drapelab: error: --version takes no other arguments\n";
    return drape::exit_input;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::RuntimeError& e) {
    // A subcommand that runs inside the parse (view, live) ends with its own status: 0, 2 for
    // bad input, 3 for a run that diverged or failed.
    return e.get_exit_code();
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() != 0) {
      if (const auto hint = drape::did_you_mean(app, std::vector<std::string>(argv + 1, argv + argc))) {
        std::cerr << *hint << "\nRun with --help for more information.\n";
        return drape::exit_input;
      }
    }
    const int code = app.exit(e);
    return code == 0 ? 0 : drape::exit_input;
  }

  try {
    if (run->parsed()) return run_command(scene_file, out_dir, overrides, quiet, overwrite, run_threads);
    if (fabrics->parsed()) return drape::list_fabrics(fabrics_json);
    if (convert->parsed()) return drape::convert_command(convert_in, convert_out);
    if (const int code = experiment_commands.dispatch(); code >= 0) return code;
    if (integrators->parsed() && table_option->count() > 0)
      return drape::print_dirk_table(dirk_table);
    if (integrators->parsed() && stability_option->count() > 0)
      return drape::with_command_line_overrides(stability_scene, stability_overrides,
                                                drape::print_stability_limit);
    return drape::list_integrators(integrators_json);
  } catch (const drape::InputError& e) {
    std::cerr << "drapelab: error: " << e.what() << "\n";
    return drape::exit_input;
  } catch (const drape::OutputError& e) {
    // The first failed write stops the run: its folder has no summary.json (docs/outputs.md).
    std::cerr << "drapelab: error: " << e.what() << "\n";
    return drape::exit_output;
  } catch (const std::exception& e) {
    std::cerr << "drapelab: failed: " << e.what() << "\n";
    return drape::exit_failure;
  }
}

int main(int argc, char** argv) { return with_standard_output_checked(run_drapelab(argc, argv)); }
