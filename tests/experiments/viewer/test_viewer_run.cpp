#include <gtest/gtest.h>

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
  EXPECT_EQ(run.energy_kinetic, std::vector<double>({0.0, 0.5}));
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
            (bad_hands / "hands.csv").string() + ": line 2: particle index out of range: 7");
}

TEST(ViewerRun, ASymbolicLinkLoopIsNamed) {
  const auto loop = testing::fresh_folder("loop") / "loop";
  std::filesystem::create_symlink(loop, loop);
  EXPECT_EQ(input_error_message([&] { read_viewer_run(loop); }),
            loop.string() + ": cannot be read: Too many levels of symbolic links");
}

}  // namespace
}  // namespace drape
