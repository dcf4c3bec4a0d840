// "Did you mean" for mistyped subcommands and options, exit status 2, and examples in --help.
#include "experiments/cli/did_you_mean.hpp"

#include <gtest/gtest.h>

#include "tests/support/drapelab_process.hpp"

namespace {

using drape::testing::run_drapelab;

TEST(DidYouMean, EditDistanceCountsInsertionsDeletionsAndSubstitutions) {
  EXPECT_EQ(drape::edit_distance("run", "run"), 0);
  EXPECT_EQ(drape::edit_distance("rnu", "run"), 2);
  EXPECT_EQ(drape::edit_distance("--outt", "--out"), 1);
  EXPECT_EQ(drape::edit_distance("", "merge"), 5);
  EXPECT_EQ(drape::edit_distance("kitten", "sitting"), 3);
}

TEST(DidYouMean, NearestNameOnlyWhenCloseEnough) {
  const std::vector<std::string> subs = {"run", "integrators", "convert", "experiment", "merge",
                                         "report"};
  EXPECT_EQ(drape::nearest_name("rnu", subs), "run");
  EXPECT_EQ(drape::nearest_name("experimnet", subs), "experiment");
  EXPECT_EQ(drape::nearest_name("integrator", subs), "integrators");
  EXPECT_EQ(drape::nearest_name("banana", subs), std::nullopt);
}

TEST(DidYouMean, MistypedSubcommandExitsWithTwoNamingTheNearest) {
  const auto r = run_drapelab("rnu scene.json --out x");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("unknown subcommand 'rnu'; did you mean 'run'?"), std::string::npos)
      << r.err;
}

TEST(DidYouMean, MistypedOptionExitsWithTwoNamingTheNearest) {
  auto r = run_drapelab("run scene.json --outt x");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("drapelab run: unknown option '--outt'; did you mean '--out'?"),
            std::string::npos)
      << r.err;
  r = run_drapelab("experiment exp.json --out x --jobz=2");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("unknown option '--jobz'; did you mean '--jobs'?"), std::string::npos)
      << r.err;
}

TEST(DidYouMean, FarFromEveryNameKeepsTheParsersMessage) {
  const auto r = run_drapelab("zzzzzzzz");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err.find("did you mean"), std::string::npos) << r.err;
}

TEST(DrapelabHelp, EverySubcommandShowsExamples) {
  for (const char* sub : {"run", "integrators", "convert", "experiment", "merge", "report"}) {
    const auto r = run_drapelab(std::string(sub) + " --help");
    EXPECT_EQ(r.exit_code, 0) << sub;
    EXPECT_NE(r.out.find("Example"), std::string::npos) << sub << ":\n" << r.out;
    EXPECT_NE(r.out.find(std::string("drapelab ") + sub), std::string::npos) << sub;
  }
}

}  // namespace
