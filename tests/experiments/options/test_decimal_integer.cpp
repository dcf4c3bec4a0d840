// decimal_integer (experiments/options/decimal_integer.hpp): integer options are read in base 10,
// whatever CLI11's base-0 conversion would make of a leading 0 or 0x.
#include "experiments/options/decimal_integer.hpp"

#include <gtest/gtest.h>

#include <string>
#include <utility>

namespace {

// The validator's verdict ("" when accepted) and the text it leaves for CLI11 to convert.
std::pair<std::string, std::string> transformed(std::string text) {
  const std::string error = drape::decimal_integer()(text);
  return {error, text};
}

TEST(DecimalInteger, LeadingZerosAreDroppedNotOctal) {
  using Result = std::pair<std::string, std::string>;
  EXPECT_EQ(transformed("010"), Result("", "10"));
  EXPECT_EQ(transformed("8080"), Result("", "8080"));
  EXPECT_EQ(transformed("-007"), Result("", "-7"));
  EXPECT_EQ(transformed("+042"), Result("", "+42"));
  EXPECT_EQ(transformed("000"), Result("", "0"));
  EXPECT_EQ(transformed("-0"), Result("", "-0"));
}

TEST(DecimalInteger, AnythingButDigitsIsRefusedNamingTheText) {
  for (const char* bad : {"0x50", "", "-", "+", "1e3", "1.0", " 8", "8 ", "--1", "12a"}) {
    const auto [error, text] = transformed(bad);
    EXPECT_EQ(error, std::string("expected a decimal integer, got '") + bad + "'") << bad;
  }
}

}  // namespace
