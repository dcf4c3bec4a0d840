// Bounded JSON text: nesting depth and shortened values (docs/scene.md, Limits).
#include <gtest/gtest.h>

#include <fstream>

#include "core/scene/json_reader.hpp"
#include "core/scene/json_text.hpp"
#include "tests/support/test_support.hpp"

namespace drape {
namespace {

using testing::input_error_message;

std::string nested(int depth) { return std::string(depth, '[') + std::string(depth, ']'); }

TEST(JsonText, NestingUpToTheLimitParses) {
  EXPECT_EQ(parse_json_text(nested(max_json_depth), "f.json").dump(),
            nested(max_json_depth));
}

TEST(JsonText, DeeperNestingIsAnInputErrorNotACrash) {
  // A million levels would overflow the stack of any recursive printer or destructor.
  EXPECT_EQ(input_error_message([] { parse_json_text(nested(1'000'000), "f.json", "line 3"); }),
            "f.json: line 3: not accepted JSON: nested deeper than 64 levels");
  const std::string file = ::testing::TempDir() + "deep_scene.json";
  std::ofstream(file) << "{\"cloth\": " << nested(100'000) << "}";
  EXPECT_EQ(input_error_message([&] { read_json_file(file); }),
            file + ": not accepted JSON: nested deeper than 64 levels");
}

TEST(JsonText, TryParseFallsBackOnSyntaxButNotOnDepth) {
  EXPECT_FALSE(try_parse_json_text("leapfrog", "--set", "integrator.name").has_value());
  EXPECT_EQ(*try_parse_json_text("[1, 2]", "--set", "x"), nlohmann::json({1, 2}));
  EXPECT_EQ(input_error_message([] { try_parse_json_text(nested(100), "--set", "x"); }),
            "--set: x: not accepted JSON: nested deeper than 64 levels");
}

TEST(JsonText, QuotedValuesAreShortAndShallow) {
  EXPECT_EQ(quote_json(nlohmann::json({1, 2})), "[1, 2]");
  EXPECT_EQ(quote_json(nlohmann::json::parse(nested(10))), "[[[[[...]]]]]");
  const std::string quoted = quote_json(std::string(50'000'000, 'x'));
  EXPECT_EQ(quoted.size(), max_quoted_chars);
  EXPECT_EQ(quoted.substr(0, 4), "\"xxx");
  EXPECT_EQ(quoted.substr(quoted.size() - 3), "...");
}

}  // namespace
}  // namespace drape
