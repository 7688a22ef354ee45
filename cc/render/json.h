// A minimal JSON reader (RFC 8259) for the few small files the renderer reads:
// data/manifest.json (scene cameras and lights) and
// data/cache/scenes/index.json (where each scene's mesh is). Also the string
// quoting used by the tools that write JSON lines.
//
// Whole document in memory, values as a tree. Numbers are doubles; strings are
// UTF-8 (\uXXXX escapes, surrogate pairs included, are decoded to UTF-8).
// Object members keep file order; a repeated key keeps its last value. Errors
// name the file, line and reason. Nesting deeper than 200 levels is an error.
#ifndef KDTREE_CC_RENDER_JSON_H_
#define KDTREE_CC_RENDER_JSON_H_

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "absl/status/statusor.h"

namespace kdtree {

class JsonValue {
 public:
  enum class Type { kNull, kBool, kNumber, kString, kArray, kObject };

  JsonValue() = default;
  static JsonValue Null() { return JsonValue(); }
  static JsonValue Bool(bool b);
  static JsonValue Number(double d);
  static JsonValue String(std::string s);
  static JsonValue Array(std::vector<JsonValue> items);
  static JsonValue Object(std::vector<std::pair<std::string, JsonValue>> members);

  Type type() const { return type_; }
  bool is_null() const { return type_ == Type::kNull; }
  bool is_bool() const { return type_ == Type::kBool; }
  bool is_number() const { return type_ == Type::kNumber; }
  bool is_string() const { return type_ == Type::kString; }
  bool is_array() const { return type_ == Type::kArray; }
  bool is_object() const { return type_ == Type::kObject; }

  // Values of the matching type (false / 0 / "" / empty otherwise).
  bool bool_value() const { return bool_; }
  double number() const { return number_; }
  const std::string& string() const { return string_; }
  const std::vector<JsonValue>& items() const { return items_; }
  const std::vector<std::pair<std::string, JsonValue>>& members() const { return members_; }

  // Object member by key (the last one of that name); nullptr when absent or
  // when this is not an object.
  const JsonValue* Find(const std::string& key) const;

 private:
  Type type_ = Type::kNull;
  bool bool_ = false;
  double number_ = 0;
  std::string string_;
  std::vector<JsonValue> items_;
  std::vector<std::pair<std::string, JsonValue>> members_;
};

// Parses one JSON document (surrounding whitespace allowed, nothing else).
// `filename` is only used in error messages: "file:line: reason".
absl::StatusOr<JsonValue> ParseJson(const std::string& text, const std::string& filename);

// Reads and parses a file; errors name the file.
absl::StatusOr<JsonValue> LoadJsonFile(const std::string& path);

// A JSON string literal, quotes included (control characters escaped, bytes
// >= 0x80 passed through as UTF-8).
std::string JsonQuote(const std::string& s);

// A JSON number: %.10g for finite values, null for NaN or infinity.
std::string JsonNumber(double d);

// A JSON array of JsonNumbers, e.g. every timed run of a step.
std::string JsonNumberArray(const std::vector<double>& values);

// The median of timed runs (mean of the middle two for an even count; 0 for
// none): the figure the report quotes of repeated timings.
double Median(std::vector<double> values);

}  // namespace kdtree

#endif  // KDTREE_CC_RENDER_JSON_H_
