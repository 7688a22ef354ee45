// Shared by the mesh syntax checks (mesh_syntax.h): text lines with numbers,
// and "file:line: reason" errors. Internal to cc/io.
#ifndef KDTREE_CC_IO_SYNTAX_LINES_H_
#define KDTREE_CC_IO_SYNTAX_LINES_H_

#include <string>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_split.h"
#include "absl/strings/string_view.h"

namespace kdtree {
namespace syntax {

inline absl::Status LineError(const std::string& name, size_t line, const std::string& why) {
  return absl::InvalidArgumentError(absl::StrCat(name, ":", line, ": ", why));
}

// Lines of `data` ('\n' or "\r\n") with 1-based numbers; '#' comments removed
// when asked; tokens separated by spaces and tabs. A line with another
// control character (assimp's readers end a line at '\r', '\f' or '\0') stops
// the reading: Next() returns false and bad() is set.
class Lines {
 public:
  Lines(absl::string_view data, bool strip_comments) : data_(data), strip_(strip_comments) {}
  // Next line's tokens (may be empty); false at the end or on a bad line.
  bool Next(std::vector<absl::string_view>* tokens) {
    if (pos_ >= data_.size() || bad_) return false;
    size_t end = data_.find('\n', pos_);
    if (end == absl::string_view::npos) end = data_.size();
    absl::string_view line = data_.substr(pos_, end - pos_);
    pos_ = end + 1;
    ++number_;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    for (char c : line) {
      if ((static_cast<unsigned char>(c) < 0x20 && c != '\t') || c == 0x7f) {
        bad_ = true;
        bad_char_ = static_cast<unsigned char>(c);
        return false;
      }
    }
    if (strip_) line = line.substr(0, line.find('#'));
    *tokens = absl::StrSplit(line, absl::ByAnyChar(" \t"), absl::SkipEmpty());
    return true;
  }
  size_t number() const { return number_; }
  size_t offset() const { return pos_ > data_.size() ? data_.size() : pos_; }
  bool bad() const { return bad_; }
  // The error of a line that stopped Next(), or `otherwise`.
  absl::Status Error(const std::string& name, const std::string& otherwise) const {
    if (!bad_) return LineError(name, number_, otherwise);
    return LineError(name, number_,
                     absl::StrFormat("control character 0x%02x in a text line", bad_char_));
  }

 private:
  absl::string_view data_;
  bool strip_;
  size_t pos_ = 0, number_ = 0;
  bool bad_ = false;
  unsigned bad_char_ = 0;
};

inline std::string Quote(absl::string_view t) {
  return absl::StrCat("'", t.substr(0, 40), t.size() > 40 ? "...'" : "'");
}

inline bool IsNumber(absl::string_view t) {
  double d;
  return absl::SimpleAtod(t, &d);
}

// PLY (ply_syntax.cc): see mesh_syntax.h.
absl::Status CheckPly(absl::string_view data, const std::string& name);

}  // namespace syntax
}  // namespace kdtree

#endif  // KDTREE_CC_IO_SYNTAX_LINES_H_
