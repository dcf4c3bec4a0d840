// Merging the runs of shards that ran elsewhere (docs/experiments.md, "Shards"): only runs of
// the same experiment and of its plan, and only from folders whose experiment.json is whole.
#include <gtest/gtest.h>

#include <iterator>

#include <sys/stat.h>

#include "experiments/sweep/experiment_merge.hpp"
#include "experiments/sweep/experiment_runner.hpp"
#include "tests/experiments/sweep/experiment_fixtures.hpp"
#include "tests/support/test_support.hpp"

namespace {

using namespace drape::experiment_fixtures;

// Merge takes a run only from a folder of the same experiment, and only when the run's
// run.json is the plan's run: a definition with other metrics but the same values has the same
// plan (ids), and an edited run.json is another run.
TEST(ExperimentMerge, TakesRunsOnlyOfThisExperimentAndItsPlannedRuns) {
  const SmallExperiment small("merge_checks");
  drape::run_experiment(small.experiment, small.options);
  const fs::path ours = small.dir / "merged";
  json other_source = two_by_three();
  other_source["metrics"] = json::array({"vibration"});
  drape::ExperimentOptions other = small.options;
  other.out_dir = small.dir / "other";
  drape::run_experiment(parse(other_source, small.dir), other);
  ASSERT_EQ(drape::merge_results(ours, {small.options.out_dir}).size(), 0u);
  try {
    drape::merge_results(ours, {other.out_dir});
    ADD_FAILURE() << "merged a folder of another experiment";
  } catch (const drape::InputError& e) {
    EXPECT_EQ(e.field(), "metrics");
    EXPECT_NE(std::string(e.what()).find("not a folder of the same experiment"), std::string::npos);
  }
  // An edited run.json: the run is no longer the plan's, in the merged folder or in a source.
  const fs::path edited = ours / "runs" / small.plan[2].id / "run.json";
  json spec = read_json(edited);
  spec["scene"] = "another_scene.json";
  std::ofstream(edited) << spec;
  const fs::path source_spec = small.options.out_dir / "runs" / small.plan[2].id / "run.json";
  std::ofstream(source_spec) << spec;
  const std::string not_planned = ": is not this run of the plan";
  EXPECT_EQ(drape::merge_results(ours, {small.options.out_dir}),
            std::vector<std::string>({small.plan[2].id + ": " + edited.string() + not_planned +
                                      "; " + source_spec.string() + not_planned}));
  // A source's damaged result.json is named with its run (the run read as not yet run).
  fs::remove_all(ours / "runs" / small.plan[1].id);
  const fs::path damaged = small.options.out_dir / "runs" / small.plan[1].id / "result.json";
  std::ofstream(damaged) << "{\"id\": ";
  EXPECT_EQ(drape::merge_results(ours, {small.options.out_dir}),
            std::vector<std::string>(
                {small.plan[1].id + ": " + damaged.string() + ": is not valid JSON",
                 small.plan[2].id + ": " + edited.string() + not_planned + "; " +
                     source_spec.string() + not_planned}));
}

// Two folders with a finished result of one run: the wall and CPU time (and the machine, the
// build) may differ, the outcome may not (keeping the first without a word would hide it).
TEST(ExperimentMerge, TwoDifferentResultsOfOneRunAreRefused) {
  const SmallExperiment small("merge_disagree");
  drape::run_experiment(small.experiment, small.options);
  const fs::path ours = small.dir / "merged", copy = small.dir / "copy";
  ASSERT_EQ(drape::merge_results(ours, {small.options.out_dir}).size(), 0u);
  fs::copy(small.options.out_dir, copy, fs::copy_options::recursive);
  const fs::path result = copy / "runs" / small.plan[0].id / "result.json";
  json row = read_json(result);
  row["wall_seconds"] = row["wall_seconds"].get<double>() + 1.0;
  row["cpu_seconds"] = row["cpu_seconds"].get<double>() + 1.0;
  std::ofstream(result) << row;
  EXPECT_EQ(drape::merge_results(ours, {copy}).size(), 0u);
  row["energy_final"] = 123.0;
  std::ofstream(result) << row;
  try {
    drape::merge_results(ours, {copy});
    ADD_FAILURE() << "merged two results of one run";
  } catch (const drape::InputError& e) {
    EXPECT_EQ(e.file(), result.string());
    EXPECT_EQ(e.field(), "energy_final");
    EXPECT_NE(std::string(e.what()).find("two results of one run"), std::string::npos) << e.what();
  }
}

// A merged folder that cannot be created is the command line's DIR, exit 2, not a raw
// filesystem error.
TEST(ExperimentMerge, AFolderThatCannotBeCreatedIsNamed) {
  const SmallExperiment small("merge_into_file");
  drape::run_experiment(small.experiment, small.options);
  const fs::path file = small.dir / "a_file";
  std::ofstream(file) << "x";
  for (const fs::path& out : {file, file / "sub"}) {
    try {
      drape::merge_results(out, {small.options.out_dir});
      ADD_FAILURE() << "merged into " << out;
    } catch (const drape::InputError& e) {
      EXPECT_EQ(e.file(), out.string());
      EXPECT_EQ(e.field(), "DIR");
      EXPECT_NE(std::string(e.what()).find("cannot be created"), std::string::npos) << e.what();
    }
  }
}

// A damaged or crafted experiment.json is named field by field (exit 2), and a plan id that
// is a path is refused before anything is removed (a "../victim" id removed a folder outside).
TEST(ExperimentMerge, ChecksTheHeaderItReads) {
  const SmallExperiment small("merge_header");
  drape::run_experiment(small.experiment, small.options);
  const fs::path header_file = small.options.out_dir / "experiment.json";
  const json header = read_json(header_file);
  const fs::path victim = small.dir / "victim";
  fs::create_directories(victim);
  const auto field_of = [&](const json& damaged) {
    std::ofstream(header_file) << damaged;
    try {
      drape::merge_results(small.options.out_dir, {});
    } catch (const drape::InputError& e) {
      EXPECT_EQ(e.file(), header_file.string());
      return e.field();
    }
    return std::string("<no error>");
  };
  json crafted = header;
  crafted["plan"][0]["id"] = "../../victim";
  EXPECT_EQ(field_of(crafted), "plan[0].id");
  crafted["plan"][0]["id"] = victim.string();
  EXPECT_EQ(field_of(crafted), "plan[0].id");
  EXPECT_TRUE(fs::exists(victim));
  json damaged = header;
  damaged.erase("question");
  EXPECT_EQ(field_of(damaged), "question");
  damaged = header;
  damaged["metrics"] = json::array({1});
  EXPECT_EQ(field_of(damaged), "metrics");
  damaged = header;
  damaged["plan"][1] = 7;
  EXPECT_EQ(field_of(damaged), "plan[1]");
  damaged = header;
  damaged["plan_size"] = header["plan"].size() + 1;
  EXPECT_EQ(field_of(damaged), "plan_size");
  EXPECT_EQ(field_of(header), "<no error>");
  // A new DIR is made only once the first source's header is read.
  const fs::path fresh = small.dir / "fresh";
  EXPECT_THROW(drape::merge_results(fresh, {victim}), drape::InputError);
  EXPECT_FALSE(fs::exists(fresh));
}

// A run whose result.json says it finished but whose file is gone, cut or no file (a named
// pipe) is named, exit 2, in a source or in DIR: listed as finished, the report would drop its
// metrics without a word.
TEST(ExperimentMerge, NamesARunFileThatIsMissingCutOrNoFile) {
  const SmallExperiment small("merge_damaged_runs");
  drape::run_experiment(small.experiment, small.options);
  const fs::path run = small.options.out_dir / "runs" / small.plan[0].id;
  const fs::path merged = small.dir / "merged";
  const auto file_named = [&] {
    try {
      drape::merge_results(merged, {small.options.out_dir});
    } catch (const drape::InputError& e) {
      return e.file();
    }
    return std::string("<no error>");
  };
  for (const char* name : {"summary.json", "energy.csv", "state.csv"}) {
    const fs::path file = run / name;
    std::ifstream in(file, std::ios::binary);
    const std::string whole{std::istreambuf_iterator<char>(in), {}};
    in.close();
    fs::remove(file);
    EXPECT_EQ(file_named(), file.string()) << "missing";
    std::ofstream(file, std::ios::binary) << whole.substr(0, 50);
    EXPECT_EQ(file_named(), file.string()) << "cut";
    fs::remove(file);
    ASSERT_EQ(mkfifo(file.c_str(), 0600), 0);
    EXPECT_EQ(file_named(), file.string()) << "a named pipe";
    fs::remove(file);
    std::ofstream(file, std::ios::binary) << whole;
  }
  // energy.csv cut at a line's end: whole lines, but its rows stop short of the run's end.
  {
    const fs::path energy = run / "energy.csv";
    std::ifstream in(energy, std::ios::binary);
    const std::string whole{std::istreambuf_iterator<char>(in), {}};
    in.close();
    const std::size_t second_line = whole.find('\n', whole.find('\n') + 1);
    std::ofstream(energy, std::ios::binary) << whole.substr(0, second_line + 1);
    EXPECT_EQ(file_named(), energy.string()) << "cut at a line's end";
    std::ofstream(energy, std::ios::binary) << whole;
  }
  const fs::path pipe = run / "notes";
  ASSERT_EQ(mkfifo(pipe.c_str(), 0600), 0);
  EXPECT_EQ(file_named(), pipe.string()) << "a named pipe that is no run file";
  EXPECT_FALSE(fs::exists(merged / "runs" / small.plan[0].id)) << "a damaged run is not copied";
  fs::remove(pipe);
  EXPECT_EQ(file_named(), "<no error>");
  const fs::path lost = merged / "runs" / small.plan[1].id / "energy.csv";
  fs::remove(lost);
  EXPECT_EQ(file_named(), lost.string());
}

}  // namespace
