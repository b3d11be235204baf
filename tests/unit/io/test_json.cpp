// The JSON writer of summary.json: layout, escaping and number formatting against texts written out by hand.
#include "signorini/io/json.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

namespace signorini {
namespace {

TEST(JsonWriter, NestsObjectsAndArraysTwoSpacesPerLevelWithCommasBetweenEntries) {
  JsonWriter w;
  w.BeginObject()
      .String("status", "converged")
      .BeginObject("contact")
      .Integer("active_pairs", 12)
      .Numbers("contact_force", {0, 2.5})
      .EndObject()
      .BeginArray("history")
      .BeginObject()
      .Integer("step", 1)
      .Bool("changed", false)
      .EndObject()
      .BeginObject()
      .Integer("step", 2)
      .Bool("changed", true)
      .EndObject()
      .EndArray()
      .EndObject();
  EXPECT_EQ(w.Text(), "{\n"
                      "  \"status\": \"converged\",\n"
                      "  \"contact\": {\n"
                      "    \"active_pairs\": 12,\n"
                      "    \"contact_force\": [0, 2.5]\n"
                      "  },\n"
                      "  \"history\": [\n"
                      "    {\n"
                      "      \"step\": 1,\n"
                      "      \"changed\": false\n"
                      "    },\n"
                      "    {\n"
                      "      \"step\": 2,\n"
                      "      \"changed\": true\n"
                      "    }\n"
                      "  ]\n"
                      "}\n");
}

TEST(JsonWriter, EscapesQuotesBackslashesAndControlCharactersInKeysAndValues) {
  JsonWriter w;
  w.BeginObject().String("a\"b", "say \"hi\"\\ C:\\dir\nnext\ttab\x01\x1f end").EndObject();
  // Control characters (below 0x20) as \u00XX with lower-case hex digits; everything else as it is, UTF-8 included.
  EXPECT_EQ(w.Text(), "{\n  \"a\\\"b\": \"say \\\"hi\\\"\\\\ C:\\\\dir\\u000anext\\u0009tab\\u0001\\u001f end\"\n}\n");
  JsonWriter u;
  u.BeginObject().String("unit", "\xc2\xb5m \x7f").EndObject();
  EXPECT_EQ(u.Text(), "{\n  \"unit\": \"\xc2\xb5m \x7f\"\n}\n");
}

TEST(JsonWriter, WritesNumbersWithTenSignificantDigitsAndNonFiniteAsNull) {
  const struct {
    double value;
    const char *text;
  } cases[] = {{0.1, "0.1"},
               {1.0 / 3.0, "0.3333333333"},
               {2.0 / 3.0, "0.6666666667"},
               {-12345678901.0, "-1.23456789e+10"},
               {1234567890.0, "1234567890"},
               {1e-300, "1e-300"},
               {6.02214076e23, "6.02214076e+23"},
               {0.0, "0"},
               {-0.0, "-0"},
               {std::numeric_limits<double>::quiet_NaN(), "null"},
               {std::numeric_limits<double>::infinity(), "null"},
               {-std::numeric_limits<double>::infinity(), "null"}};
  for (const auto &c : cases) {
    JsonWriter w;
    w.BeginObject().Number("x", c.value).EndObject();
    EXPECT_EQ(w.Text(), std::string("{\n  \"x\": ") + c.text + "\n}\n") << c.text;
    JsonWriter list;
    list.BeginObject().Numbers("x", {1, c.value}).EndObject();
    EXPECT_EQ(list.Text(), std::string("{\n  \"x\": [1, ") + c.text + "]\n}\n") << c.text;
  }
}

TEST(JsonWriter, WritesIntegersExactlyEvenBeyondADoublesMantissa) {
  JsonWriter w;
  w.BeginObject()
      .Integer("big", 9007199254740993LL)
      .Integer("min", std::numeric_limits<long long>::min())
      .Numbers("empty", {})
      .EndObject();
  EXPECT_EQ(w.Text(), "{\n  \"big\": 9007199254740993,\n  \"min\": -9223372036854775808,\n  \"empty\": []\n}\n");
}

} // namespace
} // namespace signorini
