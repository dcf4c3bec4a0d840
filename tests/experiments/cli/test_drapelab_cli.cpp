// `drapelab run` end to end: files written, exit codes, messages (docs/model.md section 9).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

namespace {

namespace fs = std::filesystem;

struct Result {
  int exit_code;
  std::string err;
};

std::string read_text(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

Result drapelab(const std::string& args) {
  // ctest runs tests in parallel processes: each test gets its own stderr file.
  const fs::path err = fs::path(::testing::TempDir()) /
                       (std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) +
                        "_stderr.txt");
  const std::string cmd = std::string(DRAPELAB_EXE) + " " + args + " 2> " + err.string() + " > /dev/null";
  const int status = std::system(cmd.c_str());
  // A child killed by a signal (a sanitizer's abort) has no exit status: report it as the
  // shell would, 128 + signal, never as 0.
  const int code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  Result r{code, read_text(err)};
  EXPECT_EQ(r.err.find("Sanitizer"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("runtime error:"), std::string::npos) << r.err;
  return r;
}

fs::path write_scene(const std::string& name, const nlohmann::json& scene) {
  const fs::path file = fs::path(::testing::TempDir()) / name;
  std::ofstream(file) << scene.dump(2);
  return file;
}

nlohmann::json hanging_cloth() {
  return nlohmann::json::parse(R"({
    "cloth": {"rows": 6, "cols": 6, "spacing": 0.02, "origin": [0, 1.4, 0.2],
              "particle_mass": 0.001, "k_structural": 20, "damping_spring": 0.01},
    "pins": [[0, 0], [0, 5]],
    "dummy": null,
    "integrator": {"name": "leapfrog", "dt": 0.001},
    "duration": 0.2,
    "output": {"energy_interval": 0.05}
  })");
}

TEST(DrapelabRun, WritesSummaryEnergyAndState) {
  const fs::path out = fs::path(::testing::TempDir()) / "run_ok";
  fs::remove_all(out);
  const Result r = drapelab("run " + write_scene("ok.json", hanging_cloth()).string() + " --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto summary = nlohmann::json::parse(read_text(out / "summary.json"));
  EXPECT_EQ(summary["status"], "ok");
  EXPECT_EQ(summary["integrator"], "leapfrog");
  EXPECT_EQ(summary["steps"], 200);
  EXPECT_DOUBLE_EQ(summary["sim_time"].get<double>(), 0.2);
  EXPECT_EQ(summary["rhs_evals"], 201);
  for (const char* key : {"dt", "wall_seconds", "cpu_seconds", "energy_initial", "energy_final",
                          "energy_drift_max_rel", "events"})
    EXPECT_TRUE(summary.contains(key)) << key;

  std::istringstream energy(read_text(out / "energy.csv"));
  std::string line;
  std::getline(energy, line);
  EXPECT_EQ(line, "t,kinetic,spring,gravity,collision,total");
  int rows = 0;
  while (std::getline(energy, line)) ++rows;
  EXPECT_EQ(rows, 5) << "t = 0, 0.05, 0.1, 0.15, 0.2";

  std::istringstream state(read_text(out / "state.csv"));
  std::getline(state, line);
  EXPECT_EQ(line, "index,row,col,x,y,z,vx,vy,vz,fixed");
  std::getline(state, line);
  EXPECT_EQ(line.substr(0, 6), "0,0,0,");
  EXPECT_EQ(line.back(), '1') << "particle 0 is pinned";
  rows = 1;
  while (std::getline(state, line)) ++rows;
  EXPECT_EQ(rows, 36);
}

TEST(DrapelabRun, SetOverridesAreValidatedLikeTheFile) {
  const fs::path scene = write_scene("set.json", hanging_cloth());
  Result r = drapelab("run " + scene.string() + " --out /tmp/unused --set cloth.spacing=-0.1");
  EXPECT_EQ(r.exit_code, 2);
  // The value came from --set: the error names the argument (the scene's own would name the scene).
  EXPECT_NE(r.err.find("--set cloth.spacing=-0.1: cloth.spacing: must be at least 1e-06, got -0.1"), std::string::npos)
      << r.err;
  r = drapelab("run " + scene.string() + " --out /tmp/unused --set integrator.name=euler-forward");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("integrator.name: unknown integrator 'euler-forward'"), std::string::npos) << r.err;
  // The scene's integrator is leapfrog: a key only ARKODE reads is refused, not ignored.
  r = drapelab("run " + scene.string() + " --out /tmp/unused --set integrator.rtol=1e-3");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--set integrator.rtol=1e-3: integrator.rtol: not used by this run of 'leapfrog'"),
            std::string::npos)
      << r.err;
  r = drapelab("run " + scene.string() +
               " --out /tmp/unused --set integrator.name=arkode-dirk --set integrator.max_step_halvings=31");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("integrator.max_step_halvings: must be between 0 and 30"), std::string::npos)
      << r.err;
  // The stage solver, now defaulted to the line search: a name it does not know is refused.
  r = drapelab("run " + scene.string() +
               " --out /tmp/unused --set integrator.name=arkode-dirk --set integrator.nonlinear_solver=bfgs");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--set integrator.nonlinear_solver=bfgs: integrator.nonlinear_solver: "
                       "unknown nonlinear solver 'bfgs'"),
            std::string::npos)
      << r.err;
  // `live` reads its scene and --set alike (the error comes before any port is opened).
  r = drapelab("live " + scene.string() + " --port 18765 --out " +
               (fs::path(::testing::TempDir()) / "live_set").string() +
               " --set integrator.rtol=1e-3");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--set integrator.rtol=1e-3: integrator.rtol: not used by this run of"),
            std::string::npos)
      << r.err;
}

TEST(DrapelabRun, MissingFileAndBadUsageExitWithTwo) {
  Result r = drapelab("run /nonexistent/scene.json --out /tmp/unused");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("/nonexistent/scene.json: no such file"), std::string::npos) << r.err;
  EXPECT_EQ(drapelab("run").exit_code, 2);
  EXPECT_EQ(drapelab("frobnicate").exit_code, 2);
  // --version alone prints it; with anything else (which CLI11 would ignore) it is refused.
  EXPECT_EQ(drapelab("--version").exit_code, 0);
  for (const std::string args : {"--version extra", "extra --version", "--version --version"}) {
    const Result v = drapelab(args);
    EXPECT_EQ(v.exit_code, 2) << args;
    EXPECT_EQ(v.err, "drapelab: error: --version takes no other arguments\n") << args;
  }
}

TEST(DrapelabRun, DivergenceStopsWritesItsSummaryAndExitsWithThree) {
  nlohmann::json scene = hanging_cloth();
  scene["cloth"]["k_structural"] = 2000;  // sqrt(k/m) ~ 1400 rad/s: dt = 5 ms is far past stability
  scene["integrator"]["dt"] = 0.005;
  scene["duration"] = 5.0;
  const fs::path out = fs::path(::testing::TempDir()) / "run_diverged";
  fs::remove_all(out);
  const Result r = drapelab("run " + write_scene("div.json", scene).string() + " --out " + out.string());
  EXPECT_EQ(r.exit_code, 3);
  const auto summary = nlohmann::json::parse(read_text(out / "summary.json"));
  EXPECT_EQ(summary["status"], "diverged");
  EXPECT_LT(summary["time"].get<double>(), 1.0) << "stops at once";
  EXPECT_FALSE(summary["reason"].get<std::string>().empty());
  EXPECT_FALSE(fs::exists(out / "state.csv")) << "no final state is passed off as complete";
}

TEST(DrapelabRun, BadRecordingExitsWithTwoNamingFileAndLine) {
  const fs::path dir = fs::path(::testing::TempDir()) / "bad_recording";
  fs::create_directories(dir);
  {
    std::ofstream bad(dir / "hands.jsonl");
    bad << "{\"format\": \"drapelab-recording\", \"version\": 1}\n"
        << "{\"t\": 0.0, \"right\": [0, 1, 0]}\n"
        << "{\"t\": 0.1, \"right\": [0, NaN, 0]}\n";
  }
  nlohmann::json scene = hanging_cloth();
  scene["input"] = {{"recording", "hands.jsonl"}};
  std::ofstream(dir / "scene.json") << scene.dump(2);
  Result r = drapelab("run " + (dir / "scene.json").string() + " --out " + (dir / "out").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("hands.jsonl"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("line 3"), std::string::npos) << r.err;

  r = drapelab("convert " + (dir / "hands.jsonl").string() + " " + (dir / "out.jsonl").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("line 3"), std::string::npos) << r.err;
}

TEST(DrapelabRun, CombinationRunsUnderAnImplicitIntegrator) {
  const fs::path out = fs::path(::testing::TempDir()) / "c4_implicit";
  fs::remove_all(out);
  const std::string scene =
      std::string(DRAPE_SOURCE_DIR) + "/experiments/scenes/combination4_hold_release_attach.json";
  const Result r = drapelab("run " + scene + " --out " + out.string() +
                            " --set integrator.name=implicit-euler --set integrator.dt=0.005");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto summary = nlohmann::json::parse(read_text(out / "summary.json"));
  std::vector<std::string> types;
  for (const auto& e : summary["events"]) types.push_back(e["type"]);
  EXPECT_EQ(types, (std::vector<std::string>{"hold", "release", "attach", "attach_fixed"}));
  EXPECT_EQ(summary["counters"]["resets"], 4) << "restarted at each event";
}

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / name;
  fs::remove_all(dir);
  return dir;
}

// Finite but huge: the cloth explodes in its first steps and NaN reaches the dummy's queries.
nlohmann::json exploding_cloth(const std::string& collision_model) {
  nlohmann::json scene = hanging_cloth();
  scene["cloth"]["k_structural"] = 1e12;
  scene["cloth"]["particle_mass"] = 1e-9;
  scene["integrator"]["dt"] = 0.01;
  scene["duration"] = 1.0;
  scene["dummy"] = {{"builtin", "cylinder"}, {"radius", 0.05}, {"center", {0.05, 0.15}},
                    {"y_top", 1.45}, {"y_bottom", 1.2}};
  scene["collision"] = {{"model", collision_model}, {"threshold", 0.01}};
  return scene;
}

TEST(DrapelabHarden, ExplodingRunEndsDivergedWithItsSummary) {
  for (const std::string model : {"particle", "surface"}) {
    const fs::path out = fresh_dir("run_exploding_" + model);
    const Result r = drapelab("run " + write_scene("boom.json", exploding_cloth(model)).string() +
                              " --out " + out.string());
    ASSERT_EQ(r.exit_code, 3) << model << ": " << r.err;
    const auto summary = nlohmann::json::parse(read_text(out / "summary.json"));
    EXPECT_EQ(summary["status"], "diverged") << model;
    EXPECT_FALSE(fs::exists(out / "summary.json.tmp"));
  }
}

TEST(DrapelabHarden, HugeAndNonIntegerValuesExitWithTwoNamingTheField) {
  const std::string scene = write_scene("huge.json", hanging_cloth()).string();
  const struct {
    std::string set, message;
  } cases[] = {
      {"cloth.k_structural=1e308", "--set cloth.k_structural=1e308: cloth.k_structural: must be at most"},
      {"cloth.spacing=1e308", "--set cloth.spacing=1e308: cloth.spacing: must be at most 1000.0"},
      {"'pins=[[4294967296,0]]'", "--set pins=[[4294967296,0]]: pins[0]: [4294967296, 0] is off the 6 x 6 grid"},
      {"integrator.max_steps=0.5", "--set integrator.max_steps=0.5: integrator.max_steps: expected an integer, got 0.5"},
      {"integrator.max_steps=1e300", "--set integrator.max_steps=1e300: integrator.max_steps: must be an integer from 1"},
      {"cloth.rows=46341 --set cloth.cols=46341", "--set cloth.cols=46341: cloth.cols: rows x cols = 2147488281"},
      {"cloth.rows=4294967297", "--set cloth.rows=4294967297: cloth.rows: must be an integer from 1 to 4000000"},
      {"cloth.rows=20000 --set cloth.cols=20000", "--set cloth.cols=20000: cloth.cols: rows x cols = 400000000"},
      {"integrator.dt=1e-300", "--set integrator.dt=1e-300: integrator.dt: too small to advance time"},
      {"output.energy_interval=1e-300", "--set output.energy_interval=1e-300: output.energy_interval: too small to advance"},
  };
  for (const auto& c : cases) {
    const fs::path out = fresh_dir("run_huge");
    const Result r = drapelab("run " + scene + " --out " + out.string() + " --set " + c.set);
    EXPECT_EQ(r.exit_code, 2) << c.set << ": " << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.set << ": " << r.err;
    EXPECT_FALSE(fs::exists(out)) << "nothing is written for bad input";
  }
}

TEST(DrapelabHarden, DeepJsonAndNonFilesAreInputErrors) {
  const fs::path dir = fresh_dir("run_inputs");
  fs::create_directories(dir / "a_folder");
  std::ofstream(dir / "deep.json") << std::string(100000, '[') << std::string(100000, ']');
  Result r = drapelab("run " + (dir / "deep.json").string() + " --out " + (dir / "o").string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("deep.json: not accepted JSON: nested deeper than 64 levels"), std::string::npos) << r.err;
  r = drapelab("run " + (dir / "a_folder").string() + " --out " + (dir / "o").string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("a_folder: is a directory, not a file"), std::string::npos) << r.err;
  for (const std::string& recording : {(dir / "a_folder").string(), std::string("/dev/zero")}) {
    nlohmann::json scene = hanging_cloth();
    scene["input"] = {{"recording", recording}};
    r = drapelab("run " + write_scene("rec.json", scene).string() + " --out " + (dir / "o").string());
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("rec.json: input.recording: " + recording + ": "), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("no such file"), std::string::npos) << r.err;
  }
  std::ofstream(dir / "deep.jsonl") << "{\"format\": \"drapelab-recording\", \"version\": 1}\n"
                                    << std::string(100000, '[') << "\n";
  nlohmann::json scene = hanging_cloth();
  scene["input"] = {{"recording", (dir / "deep.jsonl").string()}};
  r = drapelab("run " + write_scene("rec.json", scene).string() + " --out " + (dir / "o").string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("deep.jsonl: line 2: not accepted JSON"), std::string::npos) << r.err;
}

TEST(DrapelabHarden, OutProblemsExitWithTwoBeforeTheModelIsBuilt) {
  const fs::path dir = fresh_dir("run_out_problems");
  fs::create_directories(dir);
  std::ofstream(dir / "a_file") << "x";
  const std::string scene = write_scene("out.json", hanging_cloth()).string();
  Result r = drapelab("run " + scene + " --out " + (dir / "a_file").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("a_file: --out: exists and is not a folder"), std::string::npos) << r.err;
  r = drapelab("run " + scene + " --out " + (dir / "a_file" / "sub").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--out: cannot be created"), std::string::npos) << r.err;
}

TEST(DrapelabHarden, AReusedFolderNeedsOverwriteWhichClearsTheOldRun) {
  const fs::path out = fresh_dir("run_reused");
  const std::string ok = write_scene("reuse_ok.json", hanging_cloth()).string();
  ASSERT_EQ(drapelab("run " + ok + " --out " + out.string()).exit_code, 0);
  std::ofstream(out / "notes.txt") << "mine";
  Result r = drapelab("run " + ok + " --out " + out.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(out.string() + ": --out: holds another run's files (summary.json, "
                                      "energy.csv, state.csv); pass --overwrite"),
            std::string::npos)
      << r.err;
  // A diverging rerun must not leave the old state.csv beside its new summary.
  nlohmann::json diverging = hanging_cloth();
  diverging["cloth"]["k_structural"] = 2000;
  diverging["integrator"]["dt"] = 0.005;
  diverging["duration"] = 5.0;
  r = drapelab("run " + write_scene("reuse_div.json", diverging).string() + " --out " +
               out.string() + " --overwrite");
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_EQ(nlohmann::json::parse(read_text(out / "summary.json"))["status"], "diverged");
  EXPECT_FALSE(fs::exists(out / "state.csv"));
  EXPECT_TRUE(fs::exists(out / "notes.txt")) << "only run files are cleared";
}

TEST(DrapelabHarden, AnErrorInASetValueNamesTheArgumentNotTheScene) {
  const std::string scene = write_scene("set_blame.json", hanging_cloth()).string();
  const fs::path out = fresh_dir("run_set_blame");
  Result r = drapelab("run " + scene + " --out " + out.string() + " --set nosuch=1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("drapelab: error: --set nosuch=1: nosuch: unknown key"), std::string::npos)
      << r.err;
  r = drapelab("run " + scene + " --out " + out.string() + " --set integrator.name=rk99");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--set integrator.name=rk99: integrator.name: unknown integrator 'rk99'"),
            std::string::npos)
      << r.err;
  // Among several, the --set that gave the failing value.
  r = drapelab("run " + scene + " --out " + out.string() + " --set duration=-1 --set cloth.rows=6");
  EXPECT_NE(r.err.find("--set duration=-1: duration: must not be negative"), std::string::npos)
      << r.err;
  // The same key twice: one value would be dropped without a word.
  r = drapelab("run " + scene + " --out " + out.string() + " --set duration=0.01 --set duration=0.02");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "drapelab: error: --set duration=0.02: duration: given twice (also --set "
                   "duration=0.01)\n");
}

TEST(DrapelabHarden, AFailedWriteStopsTheRunWithExitFour) {
  // A file size limit stands in for a full disk: past it every write fails (EFBIG), since
  // drapelab ignores the signal (SIGXFSZ) the kernel would otherwise kill it with. Before, the
  // run went on writing nothing and ended with exit 1 at summary.json, or died of the signal.
  const fs::path out = fresh_dir("run_full");
  nlohmann::json scene = hanging_cloth();
  scene["output"]["energy_interval"] = 0;  // a row every step: 2000 rows, about 200 kB
  scene["duration"] = 2.0;
  const fs::path err = fs::path(::testing::TempDir()) / "run_full_stderr.txt";
  const std::string cmd = "sh -c 'ulimit -f 64; exec " + std::string(DRAPELAB_EXE) +
                          " run " + write_scene("full.json", scene).string() + " --out " +
                          out.string() + "' 2> " + err.string() + " > /dev/null";
  const int status = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 4);
  const std::string message = read_text(err);
  EXPECT_NE(message.find("drapelab: error: cannot write " + (out / "energy.csv").string() +
                         ": File too large"),
            std::string::npos)
      << message;
  EXPECT_FALSE(fs::exists(out / "summary.json")) << "the folder must not look complete";
}

TEST(DrapelabHarden, AFailedWriteToStandardOutputIsExitFour) {
  // /dev/full refuses every write (ENOSPC): a table or list that reached nobody was exit 0 (the
  // printers buffer it) or exit 1 (fmt's own error), and a script took the empty result.
  for (const std::string args :
       {"integrators", "integrators --table ARKODE_SDIRK_2_1_2", "fabrics", "--version"}) {
    const std::string cmd = std::string(DRAPELAB_EXE) + " " + args + " > /dev/full 2> /dev/null";
    const int status = std::system(cmd.c_str());
    ASSERT_TRUE(WIFEXITED(status)) << args;
    EXPECT_EQ(WEXITSTATUS(status), 4) << args;
  }
}

TEST(Readme, TestCommandIsWhatCiRuns) {
  const std::string readme = read_text(fs::path(DRAPE_SOURCE_DIR) / "README.md");
  const std::string ci = read_text(fs::path(DRAPE_SOURCE_DIR) / ".ci" / "run");
  // Its first command line; the sanitizer and fuzzing steps follow it (docs/fuzzing.md).
  const std::size_t start = ci.find("./install_dependencies.sh");
  ASSERT_NE(start, std::string::npos);
  const std::string line = ci.substr(start, ci.find('\n', start) - start);
  // `|| exit 1`: under set -e, a failure before the last command of an && list goes on.
  const std::string stop = " || exit 1";
  ASSERT_EQ(line.substr(line.size() - stop.size()), stop) << line;
  const std::string command = line.substr(0, line.size() - stop.size());
  EXPECT_NE(readme.find(command), std::string::npos) << command;
}

}  // namespace
