// The runs an experiment folder already holds (docs/experiments.md, resume and merge): a run
// counts when its run.json is the plan's run and its result.json a row of it, and a finished
// run's files are all there and whole.
#include "experiments/sweep/stored_runs.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <fstream>

#include "tests/support/test_support.hpp"

namespace drape {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

fs::path fresh(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("stored_runs_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

const json planned = {{"index", 3}, {"id", "dt-0.001-ab12"}, {"scene", "s.json"},
                      {"reference", "ref-cd34"}, {"overrides", {"integrator.dt=0.001"}}};

json result_row(const std::string& status = "ok") {
  return {{"id", "dt-0.001-ab12"}, {"run_dir", "runs/dt-0.001-ab12"}, {"status", status}};
}

void write(const fs::path& file, const std::string& text) { std::ofstream(file) << text; }

TEST(StoredRuns, IdentityIsTheRunsDefinitionNotItsPlaceInThePlan) {
  const json identity = run_identity(planned);
  EXPECT_FALSE(identity.contains("index"));
  EXPECT_FALSE(identity.contains("reference"));
  EXPECT_EQ(identity["id"], "dt-0.001-ab12");
  EXPECT_EQ(identity["overrides"], json({"integrator.dt=0.001"}));
  json moved = planned;
  moved["index"] = 7;
  EXPECT_EQ(run_identity(moved), identity);
}

TEST(StoredRuns, ReadJsonIfPresentTakesOnlyWholeRegularFiles) {
  const fs::path dir = fresh("read");
  write(dir / "good.json", R"({"a": 1})");
  write(dir / "cut.json", R"({"a": )");
  EXPECT_EQ(read_json_if_present(dir / "good.json"), json({{"a", 1}}));
  EXPECT_EQ(read_json_if_present(dir / "cut.json"), std::nullopt);
  EXPECT_EQ(read_json_if_present(dir / "none.json"), std::nullopt);
  EXPECT_EQ(read_json_if_present(dir), std::nullopt) << "a folder";
  ASSERT_EQ(mkfifo((dir / "pipe.json").c_str(), 0600), 0);
  EXPECT_EQ(read_json_if_present(dir / "pipe.json"), std::nullopt) << "no wait for a writer";
}

TEST(StoredRuns, AFinishedRunNeedsItsIdentityAndAValidRow) {
  const fs::path dir = fresh("finished");
  StoredResult none = finished_run(dir, planned);
  EXPECT_FALSE(none.row);
  EXPECT_EQ(none.problem, "") << "not run yet: nothing wrong";

  write(dir / "result.json", result_row().dump());
  EXPECT_EQ(finished_run(dir, planned).problem, (dir / "run.json").string() + ": missing or unreadable");

  write(dir / "run.json", run_identity(planned).dump());
  const StoredResult done = finished_run(dir, planned);
  ASSERT_TRUE(done.row);
  EXPECT_EQ((*done.row)["status"], "ok");
  EXPECT_EQ(done.problem, "");

  json other = run_identity(planned);
  other["overrides"] = {"integrator.dt=0.002"};
  write(dir / "run.json", other.dump());
  EXPECT_EQ(finished_run(dir, planned).problem, (dir / "run.json").string() + ": is not this run of the plan");

  write(dir / "run.json", run_identity(planned).dump());
  write(dir / "result.json", "{\"id\": ");
  EXPECT_EQ(finished_run(dir, planned).problem, (dir / "result.json").string() + ": is not valid JSON");
  json wrong_status = result_row("maybe");
  write(dir / "result.json", wrong_status.dump());
  EXPECT_EQ(finished_run(dir, planned).problem,
            (dir / "result.json").string() +
                ": \"status\" is \"maybe\", not one of ok, diverged, failed, error, crashed");
}

TEST(StoredRuns, AFinishedRunsFilesMustAllBeThereAndWhole) {
  const fs::path dir = fresh("files");
  const auto refused = [&](const json& row) {
    return testing::input_error_message([&] { check_run_files(dir, row); });
  };
  EXPECT_EQ(refused(result_row("error")), "no error") << "a run that could not run wrote nothing";
  EXPECT_EQ(refused(result_row("crashed")), "no error");
  EXPECT_EQ(refused(result_row()), (dir / "summary.json").string() +
                                       ": no such file (its run finished: result.json)");
  write(dir / "summary.json", R"({"status": "ok", "sim_time": 0.1})");
  EXPECT_EQ(refused(result_row()), (dir / "energy.csv").string() +
                                       ": no such file (the run wrote it: summary.json)");
  write(dir / "energy.csv", "t,kinetic\n0,0\n0.1,");
  EXPECT_EQ(refused(result_row()), (dir / "energy.csv").string() +
                                       ": the last line is cut (the file does not end in a newline)");
  // Cut at a line's end: the rows stop more than an energy interval before sim_time.
  write(dir / "energy.csv", "t,kinetic\n0,0\n0.05,0\n");
  EXPECT_NE(refused(result_row()).find("the rows end at t = 0.05 s, before the run's sim_time"),
            std::string::npos);
  write(dir / "energy.csv", "t,kinetic\n0,0\n0.1,0\n");
  EXPECT_EQ(refused(result_row()), (dir / "state.csv").string() +
                                       ": no such file (the run wrote it: summary.json)");
  write(dir / "state.csv", "");
  EXPECT_EQ(refused(result_row()), (dir / "state.csv").string() +
                                       ": empty file (a run writes its header line first)");
  write(dir / "state.csv", "index\n0\n");
  EXPECT_EQ(refused(result_row()), "no error");
  write(dir / "summary.json", "[1]");
  EXPECT_EQ(refused(result_row()), (dir / "summary.json").string() + ": expected a JSON object");
}

TEST(StoredRuns, ABisectionNeedsItsBisectJson) {
  const fs::path dir = fresh("bisect");
  json row = result_row();
  row["bisect_parameter"] = "integrator.dt";
  EXPECT_EQ(testing::input_error_message([&] { check_run_files(dir, row); }),
            (dir / "bisect.json").string() + ": no such file (its run finished: result.json)");
  write(dir / "bisect.json", "{}");
  EXPECT_EQ(testing::input_error_message([&] { check_run_files(dir, row); }), "no error");
}

}  // namespace
}  // namespace drape
