// The strict JSON reader: types, ranges, unknown keys, file errors.
#include <gtest/gtest.h>

#include "core/scene/json_reader.hpp"
#include "tests/support/test_support.hpp"

#include <fstream>

namespace drape {
namespace {

using testing::input_error_message;

TEST(JsonReader, ReadsValuesAndDefaults) {
  const nlohmann::json j = {{"a", 1.5}, {"n", 3}, {"s", "x"}, {"v", {1, 2, 3}}, {"b", true}};
  JsonReader in(j, "f.json", "top");
  EXPECT_EQ(in.number("a"), 1.5);
  EXPECT_EQ(in.integer("n"), 3);
  EXPECT_EQ(in.string("s"), "x");
  EXPECT_EQ(in.vec3("v"), Vec3(1, 2, 3));
  EXPECT_TRUE(in.boolean("b", false));
  EXPECT_EQ(in.number("missing", 7.0), 7.0);
  EXPECT_NO_THROW(in.finish());
}

TEST(JsonReader, ErrorsNameFileAndFullPath) {
  const nlohmann::json j = {{"a", "text"}, {"extra", 1}, {"v", {1, 2}}, {"n", 1.5}};
  JsonReader in(j, "f.json", "cloth");
  EXPECT_EQ(input_error_message([&] { in.number("a"); }),
            "f.json: cloth.a: expected a number, got string");
  EXPECT_EQ(input_error_message([&] { in.number("nope"); }), "f.json: cloth.nope: required field is missing");
  EXPECT_EQ(input_error_message([&] { in.vec3("v"); }), "f.json: cloth.v: expected 3 numbers [x, y, z]");
  EXPECT_EQ(input_error_message([&] { in.integer("n"); }), "f.json: cloth.n: expected an integer, got 1.5");
  EXPECT_EQ(input_error_message([&] { in.positive("a", -1.0); }), "f.json: cloth.a: must be positive, got -1.0");
  EXPECT_EQ(input_error_message([&] { in.finish(); }), "f.json: cloth.extra: unknown key");
  const nlohmann::json huge = {{"rows", 10000000000LL}};
  JsonReader big(huge, "f.json", "cloth");
  EXPECT_EQ(input_error_message([&] { big.integer("rows"); }),
            "f.json: cloth.rows: integer out of range: 10000000000");
}

TEST(JsonReader, MissingAndBrokenFilesNameTheFile) {
  EXPECT_EQ(input_error_message([] { read_json_file("/nonexistent/scene.json"); }),
            "/nonexistent/scene.json: cannot open file");
  const std::string broken = ::testing::TempDir() + "broken.json";
  std::ofstream(broken) << "{\"cloth\": [1, 2";
  EXPECT_NE(input_error_message([&] { read_json_file(broken); }).find(broken + ": not valid JSON"),
            std::string::npos);
}

}  // namespace
}  // namespace drape
