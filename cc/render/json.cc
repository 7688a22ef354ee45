#include "cc/render/json.h"

#include <algorithm>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "cc/base/read_file.h"

namespace kdtree {
namespace {

// nlohmann's what() without its "[json.exception.parse_error.101] " tag and
// "parse error at line L, column C: " prefix (ours names the file too).
std::string Reason(const nlohmann::json::exception& e) {
  std::string s = e.what();
  if (s.rfind("[json.exception.", 0) == 0) {
    const size_t close = s.find("] ");
    if (close != std::string::npos) s = s.substr(close + 2);
  }
  if (s.rfind("parse error", 0) == 0) {
    const size_t colon = s.find(": ");
    if (colon != std::string::npos) s = s.substr(colon + 2);
  }
  return s;
}

// "line L, column C" (both 1-based) of the byte nlohmann stopped at (its
// parse_error::byte, 1-based; past the end for an unexpected end of input).
std::string Where(const std::string& text, size_t byte) {
  const size_t at = std::min(byte > 0 ? byte - 1 : 0, text.size());
  const size_t line = 1 + static_cast<size_t>(std::count(text.begin(), text.begin() + at, '\n'));
  size_t column = at + 1;
  if (at > 0) {
    const size_t newline = text.rfind('\n', at - 1);
    if (newline != std::string::npos) column = at - newline;
  }
  return absl::StrCat("line ", line, ", column ", column);
}

}  // namespace

absl::StatusOr<nlohmann::json> ParseJson(const std::string& text, const std::string& filename) {
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    return absl::InvalidArgumentError(
        absl::StrCat(filename, ": ", Where(text, e.byte), ": ", Reason(e)));
  } catch (const nlohmann::json::exception& e) {  // e.g. a number out of range
    return absl::InvalidArgumentError(absl::StrCat(filename, ": ", Reason(e)));
  }
}

absl::StatusOr<nlohmann::json> LoadJsonFile(const std::string& path) {
  absl::StatusOr<std::string> text = ReadTextInput(path, "JSON file");
  if (!text.ok()) return text.status();
  return ParseJson(*text, path);
}

}  // namespace kdtree
