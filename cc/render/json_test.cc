#include "cc/render/json.h"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "gtest/gtest.h"

namespace kdtree {
namespace {

TEST(Json, ParsesNestedDocument) {
  absl::StatusOr<nlohmann::json> v = ParseJson(
      R"({"scenes": [{"name": "bunny", "camera": {"position": [1, -2.5e1, 0.5], "fov_deg": 45},
          "light": null, "ok": true, "s": "a\"b\\c\u00e9\ud83d\ude00"}]})",
      "m.json");
  ASSERT_TRUE(v.ok()) << v.status();
  ASSERT_TRUE(v->contains("scenes"));
  const nlohmann::json& scenes = (*v)["scenes"];
  ASSERT_TRUE(scenes.is_array());
  const nlohmann::json& e = scenes[0];
  EXPECT_EQ(e["name"].get<std::string>(), "bunny");
  EXPECT_DOUBLE_EQ(e["camera"]["position"][1].get<double>(), -25.0);
  EXPECT_DOUBLE_EQ(e["camera"]["fov_deg"].get<double>(), 45.0);
  EXPECT_TRUE(e["light"].is_null());
  EXPECT_TRUE(e["ok"].get<bool>());
  EXPECT_EQ(e["s"].get<std::string>(), "a\"b\\c\xc3\xa9\xf0\x9f\x98\x80");
  EXPECT_FALSE(e.contains("missing"));
}

TEST(Json, RepeatedKeyKeepsLastValue) {
  absl::StatusOr<nlohmann::json> v = ParseJson(R"({"a": 1, "a": 2})", "x");
  ASSERT_TRUE(v.ok());
  EXPECT_EQ((*v)["a"].get<double>(), 2.0);
}

// Errors: "FILE: line L, column C: reason", at the last character nlohmann
// read.
TEST(Json, ErrorsNameFileLineAndReason) {
  const struct {
    const char* text;
    const char* where;
    const char* reason;
  } cases[] = {
      {"{\n\"a\": [1, 2,\n}", "m.json: line 3, column 1: ", "unexpected '}'"},
      {"{\"a\" 1}", "m.json: line 1, column 6: ", "expected ':'"},
      {"[1 2]", "m.json: line 1, column 4: ", "expected ']'"},
      {"\"abc", "m.json: line 1, column 5: ", "missing closing quote"},
      {"01", "m.json: line 1, column 2: ", "expected end of input"},
      {"-", "m.json: line 1, column 2: ", "expected digit after '-'"},
      {"1.", "m.json: line 1, column 3: ", "expected digit after '.'"},
      {"tru", "m.json: line 1, column 4: ", "invalid literal"},
      {"{} x", "m.json: line 1, column 4: ", "invalid literal"},
      {"\"\\ud800\"", "m.json: line 1, column ", "surrogate"},
      {"", "m.json: line 1, column 1: ", "unexpected end of input"},
      {"  \n\n  [1,\n   ]", "m.json: line 4, column 4: ", "unexpected ']'"},
  };
  for (const auto& c : cases) {
    absl::StatusOr<nlohmann::json> v = ParseJson(c.text, "m.json");
    ASSERT_FALSE(v.ok()) << c.text;
    const std::string message(v.status().message());
    EXPECT_EQ(message.rfind(c.where, 0), 0u) << c.text << " -> " << message;
    EXPECT_NE(message.find(c.reason), std::string::npos) << c.text << " -> " << message;
    EXPECT_EQ(message.find("[json.exception"), std::string::npos) << message;
  }
}

TEST(Json, NumberOutOfRangeIsAnError) {
  absl::StatusOr<nlohmann::json> v = ParseJson("[1e999]", "m.json");
  ASSERT_FALSE(v.ok());
  EXPECT_EQ(std::string(v.status().message()).rfind("m.json: ", 0), 0u) << v.status();
}

TEST(Json, DeepNestingParses) {
  absl::StatusOr<nlohmann::json> v =
      ParseJson(std::string(10000, '[') + std::string(10000, ']'), "deep");
  EXPECT_TRUE(v.ok()) << v.status();
}

TEST(Json, LoadJsonFileNamesTheFile) {
  const char* dir = std::getenv("TEST_TMPDIR");
  const std::string path = std::string(dir ? dir : "/tmp") + "/json_test_bad.json";
  std::ofstream(path) << "{\"a\": 1,\n \"b\": }\n";
  absl::StatusOr<nlohmann::json> v = LoadJsonFile(path);
  ASSERT_FALSE(v.ok());
  EXPECT_EQ(std::string(v.status().message()).rfind(path + ": line 2, column 7: ", 0), 0u)
      << v.status();
  absl::StatusOr<nlohmann::json> missing = LoadJsonFile(path + ".absent");
  ASSERT_FALSE(missing.ok());
  EXPECT_TRUE(absl::IsNotFound(missing.status()));
  EXPECT_NE(missing.status().message().find(path + ".absent"), std::string::npos);
  std::remove(path.c_str());
}

}  // namespace
}  // namespace kdtree
