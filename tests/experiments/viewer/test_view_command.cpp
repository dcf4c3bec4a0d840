// `drapelab view`: the page never replaces a file of the runs it shows, and a folder name the
// page cannot hold is named, not a raw JSON exception.
#include "experiments/viewer/view_command.hpp"

#include <gtest/gtest.h>

#include "tests/support/drapelab_process.hpp"
#include "tests/support/test_support.hpp"
#include "viewer_test_files.hpp"

namespace drape {
namespace {

namespace fs = std::filesystem;
using testing::input_error_message;

std::string view_error(const fs::path& run, const fs::path& out) {
  return input_error_message([&] { view_command({run.string()}, out.string()); });
}

TEST(ViewCommand, RefusesAnOutThatIsTheRunsOwnFileOrFolder) {
  const fs::path run = testing::tiny_run("own_out");
  const std::string summary = testing::read_text(run / "summary.json");
  EXPECT_EQ(view_error(run, run / "summary.json"),
            (run / "summary.json").string() + ": --out: is the run's own summary.json (in " +
                run.string() + "): name another HTML file");
  EXPECT_EQ(testing::read_text(run / "summary.json"), summary);
  // By another spelling, and a run file the run does not have yet.
  EXPECT_EQ(view_error(run, run / ".." / run.filename() / "frames"),
            (run / ".." / run.filename() / "frames").string() +
                ": --out: is the run's own frames (in " + run.string() +
                "): name another HTML file");
  EXPECT_EQ(view_error(run, run), run.string() + ": --out: is a folder: name the HTML file to write");
  // A place the page cannot be written is bad input named up front, not exit 4 from the write.
  EXPECT_EQ(view_error(run, "/proc/drapelab_view.html"),
            "/proc/drapelab_view.html: --out: cannot be written: No such file or directory");
  EXPECT_EQ(view_error(run, "/proc/drapelab_view/page.html"),
            "/proc/drapelab_view/page.html: --out: its folder cannot be made: No such file or "
            "directory");
  EXPECT_EQ(view_error(run, ""), "--out: is empty: name the file to write");
  EXPECT_EQ(view_error(run, run / "recording.jsonl"),
            (run / "recording.jsonl").string() + ": --out: is the run's own recording.jsonl (in " +
                run.string() + "): name another HTML file");
  view_command({run.string()}, (run / "page.html").string());
  EXPECT_TRUE(fs::is_regular_file(run / "page.html"));
  // A page that cannot be written is a failed write, exit 4, as for every file drapelab writes.
  const auto full = testing::run_drapelab("view " + run.string() + " --out /dev/full");
  EXPECT_EQ(full.exit_code, 4) << full.err;
  EXPECT_EQ(full.err, "drapelab: error: cannot write /dev/full: No space left on device\n");
}

TEST(ViewCommand, RefusesAnOutThatIsTheExperimentsOwnFile) {
  const fs::path experiment = testing::fresh_folder("own_out_experiment");
  const fs::path run = experiment / "runs" / "r1";
  fs::create_directories(run.parent_path());
  fs::copy(testing::tiny_run("own_out_experiment_run"), run);
  testing::write_text(run / "result.json", "{}");
  testing::write_text(experiment / "experiment.json", "{}");
  EXPECT_EQ(view_error(run, experiment / "results.json"),
            (experiment / "results.json").string() + ": --out: is the experiment's own " +
                "results.json (in " + experiment.string() + "): name another HTML file");
  EXPECT_EQ(view_error(run, run / "result.json"),
            (run / "result.json").string() + ": --out: is the run's own result.json (in " +
                run.string() + "): name another HTML file");
  EXPECT_EQ(testing::read_text(run / "result.json"), "{}");
}

TEST(ViewCommand, AFolderNameThatIsNotUtf8IsNamed) {
  const fs::path run = testing::fresh_folder("utf8") / "run\xff";
  fs::copy(testing::tiny_run("utf8_run"), run);
  // The message shows the byte that is no UTF-8 as \xff (printable(), input_error.hpp).
  EXPECT_EQ(view_error(run, run.parent_path() / "page.html"),
            (run.parent_path() / "run").string() + "\\xff: the folder's name is not valid UTF-8, "
                                                   "which the page needs to name the run: rename "
                                                   "the folder");
}

}  // namespace
}  // namespace drape
