// InputError's message "file: field: what is wrong" (docs/scene.md, Limits): long input cut,
// control characters and bytes of no UTF-8 sequence written as \xNN.
#include "core/io/input_error.hpp"

#include <gtest/gtest.h>

namespace drape {
namespace {

TEST(InputError, MessageNamesTheFileAndTheField) {
  const InputError e("scene.json", "cloth.rows", "must be positive, got -1");
  EXPECT_STREQ(e.what(), "scene.json: cloth.rows: must be positive, got -1");
  EXPECT_EQ(e.file(), "scene.json");
  EXPECT_EQ(e.field(), "cloth.rows");
  EXPECT_EQ(e.message(), "must be positive, got -1");
  EXPECT_STREQ(InputError("", "x", "bad").what(), "<input>: x: bad") << "no file";
  EXPECT_STREQ(InputError("a.csv", "", "line 3: bad").what(), "a.csv: line 3: bad") << "no field";
}

TEST(InputError, ShortenKeepsTheLimitWithThreeDots) {
  EXPECT_EQ(shorten("abc", 3), "abc");
  EXPECT_EQ(shorten("abcdef", 5), "ab...");
  const std::string long_text(5000, 'k');
  EXPECT_EQ(shorten(long_text).size(), 200u);
  EXPECT_EQ(shorten(long_text).substr(197), "...");
  const InputError e("f.json", long_text, long_text);
  EXPECT_EQ(e.field().size(), 200u);
  EXPECT_EQ(e.message().size(), 1000u);
  EXPECT_EQ(std::string(e.what()).size(), std::string("f.json: ").size() + 200 + 2 + 1000);
}

TEST(InputError, PrintableEscapesControlBytesAndBrokenUtf8Only) {
  EXPECT_EQ(printable("plain ascii ~"), "plain ascii ~");
  EXPECT_EQ(printable(std::string("a\0b\x1b\x7f", 5)), "a\\x00b\\x1b\\x7f");
  EXPECT_EQ(printable("tab\there\n"), "tab\\x09here\\x0a");
  // Two-, three- and four-byte sequences stay: e acute, the euro sign, a musical G clef.
  EXPECT_EQ(printable("\xc3\xa9\xe2\x82\xac\xf0\x9d\x84\x9e"), "\xc3\xa9\xe2\x82\xac\xf0\x9d\x84\x9e");
  // Overlong leads (0xC0, 0xC1), a lead above U+10FFFF (0xF5), a lone continuation byte, a
  // sequence cut by the end of the text, a lead followed by ASCII.
  EXPECT_EQ(printable("\xc0\xaf"), "\\xc0\\xaf");
  EXPECT_EQ(printable("\xf5\x80\x80\x80"), "\\xf5\\x80\\x80\\x80");
  EXPECT_EQ(printable("\x80"), "\\x80");
  EXPECT_EQ(printable("x\xe2\x82"), "x\\xe2\\x82");
  EXPECT_EQ(printable("\xc3("), "\\xc3(");
  EXPECT_STREQ(InputError("f.json", std::string("k\0y", 3), "unknown key").what(),
               "f.json: k\\x00y: unknown key");
}

}  // namespace
}  // namespace drape
