// The strict JSON reader: types, ranges, unknown keys, file errors.
#include <gtest/gtest.h>

#include "core/io/json_reader.hpp"
#include "tests/support/test_support.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

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
  // A control character in a key is written as \xNN: a NUL ended the message where it stood.
  const nlohmann::json odd = {{std::string("a\0b\x1b", 4), 1}};
  JsonReader with_odd(odd, "f.json", "cloth");
  EXPECT_EQ(input_error_message([&] { with_odd.finish(); }), "f.json: cloth.a\\x00b\\x1b: unknown key");
  // So is a byte of no UTF-8 sequence; valid UTF-8 stays as it is.
  EXPECT_EQ(printable("caf\xc3\xa9 \xff\xc3("), "caf\xc3\xa9 \\xff\\xc3(");
}

TEST(JsonReader, MissingAndBrokenFilesNameTheFile) {
  EXPECT_EQ(input_error_message([] { read_json_file("/nonexistent/scene.json"); }),
            "/nonexistent/scene.json: no such file");
  EXPECT_EQ(input_error_message([] { read_json_file(""); }),
            "<input>: the path is empty: name a file");
  const std::string broken = ::testing::TempDir() + "broken.json";
  std::ofstream(broken) << "{\"cloth\": [1, 2";
  EXPECT_NE(input_error_message([&] { read_json_file(broken); }).find(broken + ": not valid JSON"),
            std::string::npos);
}

TEST(JsonReader, IntegerInChecksTypeAndRangeIn64Bits) {
  const nlohmann::json j = {{"half", 0.5},      {"huge", 1e300},     {"wrap", 4294967296LL},
                            {"float_form", 1e8}, {"negative", -1},   {"big", 18446744073709551615ULL}};
  JsonReader in(j, "f.json", "integrator");
  EXPECT_EQ(input_error_message([&] { in.integer_in("half", 1, 1000); }),
            "f.json: integrator.half: expected an integer, got 0.5");
  EXPECT_EQ(input_error_message([&] { in.integer_in("huge", 1, 1000); }),
            "f.json: integrator.huge: must be an integer from 1 to 1000, got 1e+300");
  EXPECT_EQ(input_error_message([&] { in.integer_in("big", 1, 1000); }),
            "f.json: integrator.big: must be an integer from 1 to 1000, got 18446744073709551615");
  EXPECT_EQ(input_error_message([&] { in.integer("wrap"); }),
            "f.json: integrator.wrap: integer out of range: 4294967296");
  EXPECT_EQ(input_error_message([&] { in.integer_in("negative", 1, 1000); }),
            "f.json: integrator.negative: must be an integer from 1 to 1000, got -1");
  EXPECT_EQ(in.integer_in("float_form", 1, 1'000'000'000), 100'000'000);
  EXPECT_EQ(in.integer_in("absent", 1, 10, 7), 7);
}

TEST(JsonReader, BoundsNameTheField) {
  const nlohmann::json j = {{"k", 1e308}, {"o", {0.0, 2e6, 0.0}}};
  JsonReader in(j, "f.json", "cloth");
  EXPECT_EQ(input_error_message([&] { in.at_most("k", in.number("k"), 1e12); }),
            "f.json: cloth.k: must be at most 1000000000000.0, got 1e+308");
  EXPECT_EQ(input_error_message([&] { in.within("o", in.vec3("o"), 1e6); }),
            "f.json: cloth.o: must be within +-1000000.0");
  // JSON prints an infinity as null: a derived value that overflowed read "got null".
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(input_error_message([&] { in.at_most("k", inf, 1e12); }),
            "f.json: cloth.k: must be at most 1000000000000.0, got inf");
  EXPECT_EQ(input_error_message([&] { in.positive("k", -inf); }),
            "f.json: cloth.k: must be positive, got -inf");
  EXPECT_EQ(input_error_message([&] { in.at_least("k", std::nan(""), 1.0); }),
            "f.json: cloth.k: must be at least 1.0, got nan");
}

TEST(JsonReader, LongWrongTypedValuesAreShortenedInMessages) {
  const nlohmann::json j = {{"name", std::vector<int>(10'000'000, 7)}};
  JsonReader in(j, "f.json", "integrator");
  const std::string message = input_error_message([&] { in.string("name"); });
  EXPECT_EQ(message.rfind("f.json: integrator.name: expected a string, got [7, 7, ", 0), 0u);
  EXPECT_LE(message.size(), 300u);
  EXPECT_EQ(message.substr(message.size() - 3), "...");
}

TEST(JsonReader, DirectoriesAndDevicesAreNotReadAsFiles) {
  EXPECT_EQ(input_error_message([] { read_json_file("/tmp"); }),
            "/tmp: is a directory, not a file");
  EXPECT_EQ(input_error_message([] { read_json_file("/dev/zero"); }),
            "/dev/zero: not a regular file");
  // A symbolic link loop is said to be one, not "no such file" or a filesystem exception.
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "json_loop";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::filesystem::create_symlink(dir / "b", dir / "a");
  std::filesystem::create_symlink(dir / "a", dir / "b");
  EXPECT_EQ(input_error_message([&] { read_json_file((dir / "a").string()); }),
            (dir / "a").string() + ": Too many levels of symbolic links");
}

}  // namespace
}  // namespace drape
