// Strict parsing helpers: Split keeps empty fields, ParseFinite accepts whole finite numbers only, Join.
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
}

TEST(ParseFinite, RejectsEmptyPartialAndNonFiniteText) {
  for (const char *text : {"", "abc", "1.0x", "1,5", "0.5 ", "--1", "e5", "nan", "NaN", "-nan", "inf", "-Inf",
                           "infinity", "1e400", "-1e400"}) {
    EXPECT_FALSE(ParseFinite(text).has_value()) << "'" << text << "'";
  }
}

TEST(Join, SeparatesItems) {
  EXPECT_EQ(Join({"left", "right", "top"}, ", "), "left, right, top");
  EXPECT_EQ(Join({"only"}, ", "), "only");
  EXPECT_EQ(Join({}, ", "), "");
}

} // namespace
} // namespace signorini
