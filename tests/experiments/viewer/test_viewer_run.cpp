#include <gtest/gtest.h>
#include <sys/stat.h>

#include <array>

#include "tests/support/drapelab_process.hpp"
#include "tests/support/test_support.hpp"
#include "experiments/viewer/viewer_run.hpp"
#include "viewer_test_files.hpp"

namespace drape {
namespace {

using testing::input_error_message;

TEST(ViewerRun, ReadsTraceFramesFixedSetsAndEnergy) {
  const ViewerRun run = read_viewer_run(testing::tiny_run("read"));
  EXPECT_EQ(run.name, "drape_viewer_test_read");
  EXPECT_EQ(run.source, "trace.csv");
  ASSERT_EQ(run.frames.size(), 2u);
  EXPECT_EQ(run.frames[1].t, 0.05);
  EXPECT_FLOAT_EQ(run.frames[1].positions[4], 0.99f);
  EXPECT_EQ(run.frames[0].fixed, std::vector<int>({0}));
  EXPECT_EQ(run.frames[1].fixed, std::vector<int>({0, 1}));
  EXPECT_FALSE(run.frames[0].event);
  EXPECT_TRUE(run.frames[1].event);
  EXPECT_EQ(run.energy_kinetic, std::vector<double>({0.0, 0.5, 0.25}));
  EXPECT_TRUE(run.hands.empty());
}

TEST(ViewerRun, FinalStateWhenThereIsNoTrace) {
  const auto dir = testing::tiny_run("state");
  std::filesystem::remove(dir / "trace.csv");
  testing::write_text(dir / "state.csv",
                      "index,row,col,x,y,z,vx,vy,vz,fixed\n0,0,0,0,1,0,0,0,0,1\n"
                      "1,0,1,0,0.9,0,0,0,0,0\n");
  const ViewerRun run = read_viewer_run(dir);
  EXPECT_EQ(run.source, "state.csv");
  ASSERT_EQ(run.frames.size(), 1u);
  EXPECT_EQ(run.frames[0].t, 0.1);  // sim_time
}

TEST(ViewerRun, NotARunOrMalformedNamesFolderAndFile) {
  const auto empty = testing::fresh_folder("not_a_run");
  EXPECT_EQ(input_error_message([&] { read_viewer_run(empty); }),
            empty.string() + ": not a run folder: no summary.json (drapelab run writes it)");
  const auto short_trace = testing::tiny_run("short_trace");
  testing::write_text(short_trace / "trace.csv",
                      "t,index,x,y,z,vx,vy,vz,fixed,contact,event\n0,0,0,1,0,0,0,0,1,-1,0\n");
  EXPECT_EQ(input_error_message([&] { read_viewer_run(short_trace); }),
            (short_trace / "trace.csv").string() + ": 1 rows are not whole frames of 2 particles");
  const auto bad_summary = testing::tiny_run("bad_summary");
  testing::write_text(bad_summary / "summary.json",
                      R"({"scene": {"cloth": {"rows": 0, "cols": 2}}})");
  EXPECT_NE(input_error_message([&] {
              read_viewer_run(bad_summary);
            }).find("summary.json: scene.cloth.rows: expected an integer"),
            std::string::npos);
  const auto bad_hands = testing::tiny_run("bad_hands");
  testing::write_text(bad_hands / "hands.csv",
                      "t,hand,available,x,y,z,candidate,distance,held\n0,right,1,0,0,0,7,0,-1\n");
  EXPECT_EQ(input_error_message([&] { read_viewer_run(bad_hands); }),
            (bad_hands / "hands.csv").string() +
                ": line 2: column 'candidate' is 7, expected an integer in [-1, 1]");
}

// Values no run writes: times out of order, inf, and integers that are not (nan or 1e12 went
// through static_cast<int>, undefined behaviour), each named by file, line and column.
TEST(ViewerRun, ValuesNoRunWritesAreNamed) {
  const auto dir = testing::tiny_run("values");
  const std::string trace = "t,index,x,y,z,vx,vy,vz,fixed,contact,event\n";
  const std::string energy = "t,kinetic,spring,gravity,collision,total\n0,0,0,1,0,1\n";
  const std::string dummy = "index,section,point,x,y,z,nx,ny,nz\n";
  const std::string hands = "t,hand,available,x,y,z,candidate,distance,held\n";
  // file, its text, the message after "DIR/file: "
  const std::vector<std::array<std::string, 3>> cases = {
      {"trace.csv", trace + "0.05,0,0,1,0,0,0,0,1,-1,0\n0.05,1,0.02,1,0,0,0,0,0,-1,0\n" +
                        "0,0,0,1,0,0,0,0,1,-1,1\n0,1,0.02,0.99,0.01,0,0,0,1,-1,1\n",
       "line 4: column 't': t = 0 is not after the time before it, t = 0.05 (times must increase)"},
      {"trace.csv", trace + "0,0,0,1,0,0,0,0,7,-1,0\n0,1,0.02,1,0,0,0,0,0,-1,0\n",
       "line 2: column 'fixed' is 7, expected an integer in [0, 1]"},
      // The event flag of every row, not only until one row of the frame has it.
      {"trace.csv", trace + "0,0,0,1,0,0,0,0,1,-1,1\n0,1,0.02,1,0,0,0,0,0,-1,nan\n",
       "line 3: column 'event' is nan, expected an integer in [0, 1]"},
      {"energy.csv", energy + "0.05,inf,0,0.9,0,1.4\n", "line 3: column 'kinetic' is not a finite number: inf"},
      {"energy.csv", energy + "0,0.5,0,0.9,0,1.4\n",
       "line 3: column 't': t = 0 is not after the time before it, t = 0 (times must increase)"},
      {"dummy.csv", dummy + "0,0,0,0,1,0,0,0,1\n1,1e12,0,0,1,0,0,0,1\n",
       "line 3: column 'section' is 1000000000000, expected an integer in [0, 1]"},
      {"dummy.csv", dummy + "0,nan,0,0,1,0,0,0,1\n", "line 2: column 'section' is nan, expected an integer in [0, 0]"},
      {"dummy.csv", dummy + "0,0,0,inf,1,0,0,0,1\n", "line 2: column 'x' is not a finite number: inf"},
      {"dummy.csv", dummy + "0,0,0,0,1e300,0,0,0,1\n",
       "line 2: a coordinate of 1e+300 is not finite in single precision"},
      {"hands.csv", hands + "0,right,1,0,0,0,1,0,nan\n", "line 2: column 'held' is nan, expected an integer in [-1, 1]"},
      {"hands.csv", hands + "0,middle,1,0,0,0,1,0,-1\n", "line 2: column 'hand' is 'middle', expected left or right"},
      {"hands.csv", hands + "0,right,nan,0,0,0,1,0,-1\n",
       "line 2: column 'available' is nan, expected an integer in [0, 1]"},
      // Each hand's own times (the two hands share each time).
      {"hands.csv", hands + "0.1,left,0,0,0,0,-1,0,-1\n0.1,right,0,0,0,0,-1,0,-1\n" +
                        "0.05,left,0,0,0,0,-1,0,-1\n",
       "line 4: column 't': t = 0.05 is not after the time before it, t = 0.1 (times must increase)"}};
  for (const auto& [name, text, message] : cases) {
    testing::tiny_run("values");  // the other files as they were
    testing::write_text(dir / name, text);
    EXPECT_EQ(input_error_message([&] { read_viewer_run(dir); }), (dir / name).string() + ": " + message);
  }
  testing::tiny_run("values");
  testing::write_text(dir / "hands.csv",
                      hands + "0,right,1,0,0,0,1,0,-1\n0.1,right,1,0,0,0,0,0,-1\n");
  EXPECT_EQ(read_viewer_run(dir).hands.at(0).candidate, std::vector<int>({1, 0}));
}

// The summary fields the page shows are checked, as are the frames before a diverged run's
// last ones: an event without a numeric t, or one inf, gave a page that threw at load or drew
// no frame, with view's exit 0.
TEST(ViewerRun, FieldsAndFramesThePageCannotShowAreNamed) {
  const auto dir = testing::tiny_run("page_fields");
  const auto summary = (dir / "summary.json").string();
  const auto with_events = [&](const std::string& events) {
    testing::write_text(dir / "summary.json",
                        R"({"status": "ok", "sim_time": 0.1, "events": )" + events +
                            R"(, "scene": {"cloth": {"rows": 1, "cols": 2}}})");
    return input_error_message([&] { read_viewer_run(dir); });
  };
  EXPECT_EQ(with_events("[5]"), summary + ": events[0]: expected an event (an object)");
  EXPECT_EQ(with_events(R"([{"t": "0.05", "type": "hold"}])"),
            summary + ": events[0].t: expected a finite number");
  EXPECT_EQ(with_events(R"([{"t": 0.05}])"), summary + ": events[0].type: expected a string");
  EXPECT_EQ(with_events(R"([{"t": 0.05, "type": "hold", "particle": "1"}])"),
            summary + ": events[0].particle: expected an integer");
  EXPECT_EQ(with_events(R"([{"t": 0.05, "type": "hold", "particle": 1}])"), "no error");
  testing::write_text(dir / "summary.json",
                      R"({"status": 3, "scene": {"cloth": {"rows": 1, "cols": 2}}})");
  EXPECT_EQ(input_error_message([&] { read_viewer_run(dir); }), summary + ": status: expected a string");
  for (const auto& [field, value, message] : std::vector<std::array<std::string, 3>>{
           {"duration", "-1", "a finite number, 0 or more"},
           {"sim_time", "-0.5", "a finite number, 0 or more"},
           {"dt", "-0.01", "a finite number above 0, or null"},
           {"dt", "0", "a finite number above 0, or null"}}) {
    testing::write_text(dir / "summary.json", R"({"status": "ok", ")" + field + "\": " + value +
                                                  R"(, "scene": {"cloth": {"rows": 1, "cols": 2}}})");
    EXPECT_EQ(input_error_message([&] { read_viewer_run(dir); }),
              summary + ": " + field + ": expected " + message);
  }
  // A tiny run's two frames (t = 0 and 0.05 s) with one coordinate `bad`, in the first frame's
  // y or the last's x: view's message for it.
  const auto with_coordinate = [](const std::string& name, const std::string& first_y,
                                  const std::string& last_x) {
    const auto run = testing::tiny_run(name);
    testing::write_text(run / "trace.csv",
                        "t,index,x,y,z,vx,vy,vz,fixed,contact,event\n0,0,0," + first_y +
                            ",0,0,0,0,1,-1,0\n0,1,0.02,1,0,0,0,0,0,-1,0\n"
                            "0.05,0,0,1,0,0,0,0,1,-1,1\n0.05,1," + last_x +
                            ",0.99,0.01,0,0,0,1,-1,1\n");
    return std::make_pair(run, input_error_message([&] { read_viewer_run(run); }));
  };
  const auto not_finite = [](const std::filesystem::path& run, const std::string& t) {
    return (run / "trace.csv").string() + ": the frame at t = " + t +
           " s has a position that is not finite in single precision (only a diverged run's "
           "last frames may)";
  };
  const auto [inf, inf_message] = with_coordinate("page_inf", "1e300", "0.02");
  EXPECT_EQ(inf_message, not_finite(inf, "0"));
  // A last frame that is not finite is left out of a diverged run's page only: in a run that
  // finished it is damage (it was dropped silently, and the page ended a frame early).
  const auto [last, last_message] = with_coordinate("page_nan_last", "1", "nan");
  EXPECT_EQ(last_message, not_finite(last, "0.05"));
  testing::write_text(last / "summary.json",
                      R"({"status": "diverged", "scene": {"cloth": {"rows": 1, "cols": 2}}})");
  EXPECT_EQ(read_viewer_run(last).frames.size(), 1u);
}

// The tiny run's summary with output.trace_interval and sim_time set (its frames: 0 and 0.05 s).
void write_traced_summary(const std::filesystem::path& dir, double sim_time,
                          const std::string& status) {
  testing::write_text(dir / "summary.json",
                      R"({"status": ")" + status + R"(", "sim_time": )" +
                          std::to_string(sim_time) + R"(, "step_max": 0.04, "scene": {"cloth":
                          {"rows": 1, "cols": 2}, "output": {"trace_interval": 0.05}}})");
}

TEST(ViewerRun, ATraceCutAtAFrameBoundaryIsRefused) {
  const auto dir = testing::tiny_run("cut_trace");
  write_traced_summary(dir, 0.1, "ok");
  EXPECT_EQ(read_viewer_run(dir).frames.size(), 2u) << "0.05 is one interval before the end";
  write_traced_summary(dir, 0.11, "ok");
  EXPECT_EQ(input_error_message([&] { read_viewer_run(dir); }),
            (dir / "trace.csv").string() +
                ": the frames end at t = 0.050000 s, but the run (summary.json: sim_time "
                "0.110000 s, output.trace_interval 0.050000 s) wrote frames up to its end: the "
                "file is cut");
  // A run that stopped traced nothing of its last step (at most step_max).
  write_traced_summary(dir, 0.13, "diverged");
  EXPECT_EQ(read_viewer_run(dir).frames.size(), 2u);
  write_traced_summary(dir, 0.15, "diverged");
  EXPECT_NE(input_error_message([&] { read_viewer_run(dir); }).find("the file is cut"),
            std::string::npos);
}

// Each file the page shows that summary.json says the run wrote must be there and whole, its
// rows to the run's end: a lost or `head`-cut hands.csv, energy.csv or dummy.csv would give a
// page of part of the run, exit 0; a lost trace.csv, its final state only.
TEST(ViewerRun, AFileLostOrCutShortIsNamed) {
  const auto dir = testing::tiny_run("lost_or_cut");
  testing::write_text(dir / "summary.json",
                      R"({"status": "ok", "sim_time": 0.1, "step_max": 0.001, "object_particles": 2,
                          "scene": {"cloth": {"rows": 1, "cols": 2}, "input": {"events": []},
                                    "output": {"trace_interval": 0.05}}})");
  testing::write_text(dir / "dummy.csv", "index,section,point,x,y,z,nx,ny,nz\n"
                                         "0,0,0,0,1,0,0,0,1\n1,0,1,0,1.1,0,0,0,1\n");
  testing::write_text(dir / "hands.csv", "t,hand,available,x,y,z,candidate,distance,held\n"
                                         "0,right,1,0,0,0,1,0,-1\n0.1,right,1,0,0,0,1,0,-1\n");
  testing::write_text(dir / "state.csv", "index,row,col,x,y,z,vx,vy,vz,fixed\n"
                                         "0,0,0,0,1,0,0,0,0,1\n1,0,1,0,0.9,0,0,0,0,0\n");
  const ViewerRun whole = read_viewer_run(dir);
  EXPECT_EQ(whole.source, "trace.csv");
  EXPECT_EQ(whole.dummy_points, 2);
  // The message for `name` replaced by its first `lines` lines (none: removed), then restored.
  const auto message_with = [&](const std::string& name, std::size_t lines) {
    const std::string kept = testing::read_text(dir / name);
    std::size_t end = 0;
    for (std::size_t k = 0; k < lines; ++k) end = kept.find('\n', end) + 1;
    if (lines) testing::write_text(dir / name, kept.substr(0, end));
    else std::filesystem::remove(dir / name);
    const std::string message = input_error_message([&] { read_viewer_run(dir); });
    testing::write_text(dir / name, kept);
    return message;
  };
  for (const char* name : {"trace.csv", "dummy.csv", "hands.csv", "energy.csv"})
    EXPECT_EQ(message_with(name, 0),
              (dir / name).string() + ": no such file (the run wrote it: summary.json)");
  const std::string cut = " s in summary.json (more than output.energy_interval = 0.01 s and a "
                          "step): the file is cut";
  EXPECT_EQ(message_with("hands.csv", 2), (dir / "hands.csv").string() +
                ": the rows end at t = 0 s, before the run's sim_time = 0.1" + cut);
  EXPECT_EQ(message_with("hands.csv", 1), (dir / "hands.csv").string() +
                ": no rows, before the run's sim_time = 0.1" + cut);
  EXPECT_EQ(message_with("energy.csv", 3), (dir / "energy.csv").string() +
                ": the rows end at t = 0.05 s, before the run's sim_time = 0.1" + cut);
  EXPECT_EQ(message_with("dummy.csv", 2), (dir / "dummy.csv").string() +
                ": 1 rows, but summary.json has object_particles 2: the file is cut");
  // `head -c`: the last number may be cut short yet still parse.
  const std::string energy = testing::read_text(dir / "energy.csv");
  testing::write_text(dir / "energy.csv", energy.substr(0, energy.size() - 2));
  EXPECT_EQ(input_error_message([&] { read_viewer_run(dir); }),
            (dir / "energy.csv").string() +
                ": line 4: the last line is cut (the file does not end in a newline)");
}

TEST(ViewerRun, AFolderOrNamedPipeInAFilesPlaceIsNamedNotTakenAsAbsent) {
  const auto dir = testing::tiny_run("not_files");
  std::filesystem::remove(dir / "trace.csv");
  std::filesystem::create_directory(dir / "trace.csv");
  EXPECT_EQ(input_error_message([&] { read_viewer_run(dir); }),
            (dir / "trace.csv").string() + ": not a regular file (a run writes trace.csv as one)");
  std::filesystem::remove(dir / "trace.csv");
  ASSERT_EQ(mkfifo((dir / "trace.csv").c_str(), 0600), 0);  // opening it would block for ever
  EXPECT_EQ(input_error_message([&] { read_viewer_run(dir); }),
            (dir / "trace.csv").string() + ": not a regular file (a run writes trace.csv as one)");
}

TEST(ViewerRun, ASymbolicLinkLoopIsNamed) {
  const auto loop = testing::fresh_folder("loop") / "loop";
  std::filesystem::create_symlink(loop, loop);
  EXPECT_EQ(input_error_message([&] { read_viewer_run(loop); }),
            loop.string() + ": cannot be read: Too many levels of symbolic links");
}

}  // namespace
}  // namespace drape
