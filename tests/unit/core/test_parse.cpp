// Strict parsing helpers: Split keeps empty fields, ParseFinite and ParseInteger accept whole numbers as people write
// them only, FormatNumber, Join.
#include "signorini/core/parse.hpp"

#include <gtest/gtest.h>

namespace signorini {
namespace {

using Fields = std::vector<std::string>;

TEST(Split, KeepsEmptyFields) {
  EXPECT_EQ(Split("top:0:-1", ':'), (Fields{"top", "0", "-1"}));
  EXPECT_EQ(Split("a::b", ':'), (Fields{"a", "", "b"}));
  EXPECT_EQ(Split("a:", ':'), (Fields{"a", ""}));
  EXPECT_EQ(Split(":", ':'), (Fields{"", ""}));
  EXPECT_EQ(Split("", ':'), (Fields{""}));
  EXPECT_EQ(Split("left", ':'), (Fields{"left"}));
  EXPECT_EQ(Split("a,b:c", ','), (Fields{"a", "b:c"}));
}

TEST(ParseFinite, AcceptsWholeFiniteNumbers) {
  EXPECT_EQ(ParseFinite("1.5"), 1.5);
  EXPECT_EQ(ParseFinite("-0.1"), -0.1);
  EXPECT_EQ(ParseFinite("2e3"), 2000.0);
  EXPECT_EQ(ParseFinite("+7"), 7.0);
  EXPECT_EQ(ParseFinite("0"), 0.0);
  EXPECT_EQ(ParseFinite("1e300"), 1e300);
  EXPECT_EQ(ParseFinite(".5"), 0.5);
  EXPECT_EQ(ParseFinite("5."), 5.0);
  EXPECT_EQ(ParseFinite("-2.5E-3"), -2.5e-3);
  EXPECT_EQ(ParseFinite("1e-400"), 0.0);
}

TEST(ParseFinite, RejectsEmptyPartialAndNonFiniteText) {
  for (const char *text : {"", "abc", "1.0x", "1,5", "0.5 ", "--1", "e5", "nan", "NaN", "-nan", "inf", "-Inf",
                           "infinity", "1e400", "-1e400", "0x10", "0X1p3", "-0x1", " 1", "1e", "1e+", ".", "+", "-.e1",
                           "1.5.2", "1e2.5", "1_000"}) {
    EXPECT_FALSE(ParseFinite(text).has_value()) << "'" << text << "'";
  }
}

TEST(ParseInteger, AcceptsWholeDecimalIntegersExactly) {
  EXPECT_EQ(ParseInteger("10000"), 10000);
  EXPECT_EQ(ParseInteger("-3"), -3);
  EXPECT_EQ(ParseInteger("+7"), 7);
  EXPECT_EQ(ParseInteger("0"), 0);
  EXPECT_EQ(ParseInteger("9223372036854775807"), 9223372036854775807LL);
}

TEST(ParseInteger, RejectsOverflowAndEverythingButDigits) {
  for (const char *text : {"", "+", "-", "99999999999999999999", "9223372036854775808", "-99999999999999999999",
                           "1.5", "1e3", "0x10", " 1", "1 ", "1,000", "abc"}) {
    EXPECT_FALSE(ParseInteger(text).has_value()) << "'" << text << "'";
  }
}

TEST(FormatNumber, WritesNumbersAsPeopleDo) {
  EXPECT_EQ(FormatNumber(0), "0");
  EXPECT_EQ(FormatNumber(8), "8");
  EXPECT_EQ(FormatNumber(0.625), "0.625");
  EXPECT_EQ(FormatNumber(1e9), "1e+09");
  EXPECT_EQ(FormatNumber(-1e-300), "-1e-300");
}

TEST(Join, SeparatesItems) {
  EXPECT_EQ(Join({"left", "right", "top"}, ", "), "left, right, top");
  EXPECT_EQ(Join({"only"}, ", "), "only");
  EXPECT_EQ(Join({}, ", "), "");
}

} // namespace
} // namespace signorini
