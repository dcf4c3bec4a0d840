// Bounded JSON text: nesting depth and shortened values (docs/scene.md, Limits).
#include <gtest/gtest.h>

#include <fstream>

#include "core/io/json_reader.hpp"
#include "core/io/json_text.hpp"
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

// nlohmann's lexer ends the input at a NUL byte, so text after one was dropped silently (a
// recording line's frame, a scene's later keys): JSON text has none, so it is refused.
TEST(JsonText, ANulByteIsRefusedNotTheEndOfTheInput) {
  const std::string text = std::string("{\"t\": 0}") + '\0' + "{\"t\": -5}";
  EXPECT_EQ(input_error_message([&] { parse_json_text(text, "r.jsonl", "line 2"); }),
            "r.jsonl: line 2: not valid JSON: a NUL byte at offset 8");
  EXPECT_FALSE(try_parse_json_text(text, "--set", "x").has_value());
  const std::string file = ::testing::TempDir() + "nul_scene.json";
  std::ofstream(file, std::ios::binary) << text;
  EXPECT_EQ(input_error_message([&] { read_json_file(file); }),
            file + ": not valid JSON: a NUL byte at offset 8");
}

TEST(JsonText, ARepeatedKeyIsAnInputErrorNamingItsPath) {
  const std::string repeated =
      ": not accepted JSON: the key is repeated in its object (only one value can be kept)";
  EXPECT_EQ(input_error_message([] {
              parse_json_text(R"({"cloth": {"rows": 4, "cols": 2, "rows": 5}})", "s.json");
            }),
            "s.json: cloth.rows" + repeated);
  EXPECT_EQ(input_error_message([] {
              parse_json_text(R"({"input": {"events": [{"t": 0}, {"keys": [], "t": 1, "t": 2}]}})",
                              "s.json");
            }),
            "s.json: input.events[1].t" + repeated);
  EXPECT_EQ(input_error_message([] { parse_json_text(R"([[], {"a": 1, "a": 1}])", "s.json"); }),
            "s.json: [1].a" + repeated);
  EXPECT_EQ(input_error_message([] { parse_json_text(R"({"t": 0, "t": 1})", "r.jsonl", "line 3"); }),
            "r.jsonl: line 3.t" + repeated);
  EXPECT_EQ(input_error_message([] { try_parse_json_text(R"({"a": 1, "a": 2})", "--set", "cloth"); }),
            "--set: cloth.a" + repeated);
  const std::string file = ::testing::TempDir() + "repeated_key.json";
  std::ofstream(file) << R"({"name": "x", "scenes": [], "name": "y"})";
  EXPECT_EQ(input_error_message([&] { read_json_file(file); }), file + ": name" + repeated);
  // The same key in different objects, at any depth, is no repetition.
  EXPECT_EQ(parse_json_text(R"([{"t": 0, "a": {"t": 1}}, {"t": 2}])", "f").dump(),
            R"([{"a":{"t":1},"t":0},{"t":2}])");
}

TEST(JsonText, QuotedValuesAreShortAndShallow) {
  EXPECT_EQ(quote_json(nlohmann::json({1, 2})), "[1, 2]");
  EXPECT_EQ(quote_json(nlohmann::json::parse(nested(10))), "[[[[[...]]]]]");
  const std::string quoted = quote_json(std::string(50'000'000, 'x'));
  EXPECT_EQ(quoted.size(), max_quoted_chars);
  EXPECT_EQ(quoted.substr(0, 4), "\"xxx");
  EXPECT_EQ(quoted.substr(quoted.size() - 3), "...");
}

// A recording's line without separators is one field: quoted whole, a 60 MB line would make
// the message as long.
TEST(JsonText, QuotedTextIsCutAtACharacter) {
  EXPECT_EQ(quote_text("nan"), "\"nan\"");
  const std::string line(1000, 'x');
  EXPECT_EQ(quote_text(line), "\"" + std::string(max_quoted_chars - 3, 'x') + "...\"");
  // Two-byte characters: the cut falls on a character's first byte, never inside one.
  std::string accents;
  for (int i = 0; i < 300; ++i) accents += "\xC3\xA9";  // U+00E9
  const std::string quoted = quote_text(accents);
  EXPECT_LE(quoted.size(), max_quoted_chars + 2);
  EXPECT_TRUE(is_utf8(quoted)) << quoted;
  EXPECT_EQ(quoted.substr(quoted.size() - 4), "...\"");
}

}  // namespace
}  // namespace drape
