#include "cc/render/json.h"

#include <string>

#include "gtest/gtest.h"

namespace kdtree {
namespace {

TEST(Json, ParsesNestedDocument) {
  absl::StatusOr<JsonValue> v = ParseJson(
      R"({"scenes": [{"name": "bunny", "camera": {"position": [1, -2.5e1, 0.5], "fov_deg": 45},
          "light": null, "ok": true, "s": "a\"b\\c\u00e9\ud83d\ude00"}]})",
      "m.json");
  ASSERT_TRUE(v.ok()) << v.status();
  const JsonValue* scenes = v->Find("scenes");
  ASSERT_NE(scenes, nullptr);
  ASSERT_TRUE(scenes->is_array());
  const JsonValue& e = scenes->items()[0];
  EXPECT_EQ(e.Find("name")->string(), "bunny");
  EXPECT_DOUBLE_EQ(e.Find("camera")->Find("position")->items()[1].number(), -25.0);
  EXPECT_TRUE(e.Find("light")->is_null());
  EXPECT_TRUE(e.Find("ok")->bool_value());
  EXPECT_EQ(e.Find("s")->string(), "a\"b\\c\xc3\xa9\xf0\x9f\x98\x80");
  EXPECT_EQ(e.Find("missing"), nullptr);
}

TEST(Json, RepeatedKeyKeepsLastValue) {
  absl::StatusOr<JsonValue> v = ParseJson(R"({"a": 1, "a": 2})", "x");
  ASSERT_TRUE(v.ok());
  EXPECT_EQ(v->Find("a")->number(), 2.0);
}

TEST(Json, ErrorsNameFileAndLine) {
  const struct {
    const char* text;
    const char* message;
  } cases[] = {
      {"{\n\"a\": [1, 2,\n}", "m.json:3:"},
      {"{\"a\" 1}", "expected ':'"},
      {"[1 2]", "expected ',' or ']'"},
      {"\"abc", "unterminated string"},
      {"01", "unexpected text"},
      {"-", "malformed number"},
      {"1.", "no digits after '.'"},
      {"tru", "unexpected character"},
      {"{} x", "unexpected text after"},
      {"\"\\ud800\"", "unpaired surrogate"},
      {"", "unexpected end"},
  };
  for (const auto& c : cases) {
    absl::StatusOr<JsonValue> v = ParseJson(c.text, "m.json");
    ASSERT_FALSE(v.ok()) << c.text;
    EXPECT_NE(v.status().message().find(c.message), std::string::npos)
        << c.text << " -> " << v.status().message();
    EXPECT_NE(v.status().message().find("m.json:"), std::string::npos);
  }
}

TEST(Json, DeepNestingIsAnError) {
  EXPECT_FALSE(ParseJson(std::string(1000, '[') + std::string(1000, ']'), "deep").ok());
}

TEST(Json, QuoteEscapes) {
  EXPECT_EQ(JsonQuote("a\"b\\\n\x01"), "\"a\\\"b\\\\\\n\\u0001\"");
  EXPECT_EQ(JsonNumber(1.5), "1.5");
  EXPECT_EQ(JsonNumber(1.0 / 0.0), "null");
}

TEST(Json, NumberArrayAndMedianOfRuns) {
  EXPECT_EQ(JsonNumberArray({}), "[]");
  EXPECT_EQ(JsonNumberArray({1.5, 0.25, INFINITY}), "[1.5, 0.25, null]");
  EXPECT_EQ(Median({}), 0.0);
  EXPECT_EQ(Median({3.0, 1.0, 2.0}), 2.0);
  EXPECT_EQ(Median({4.0, 1.0, 3.0, 2.0}), 2.5);
}

}  // namespace
}  // namespace kdtree
