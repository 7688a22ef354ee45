#include "cc/scenes/xml.h"

#include <cstdint>
#include <optional>

#include "absl/strings/ascii.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"

namespace kdtree {
namespace scenes {
namespace {

bool IsNameChar(char c) {
  const unsigned char u = static_cast<unsigned char>(c);
  return absl::ascii_isalnum(u) || c == '_' || c == '-' || c == '.' || c == ':' || u >= 0x80;
}

// Appends code point `cp` as UTF-8; false when it is not a valid one.
bool AppendUtf8(uint32_t cp, std::string& out) {
  if (cp == 0 || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return false;
  if (cp < 0x80) {
    out.push_back(static_cast<char>(cp));
  } else if (cp < 0x800) {
    out.push_back(static_cast<char>(0xC0 | (cp >> 6)));
    out.push_back(static_cast<char>(0x80 | (cp & 0x3F)));
  } else if (cp < 0x10000) {
    out.push_back(static_cast<char>(0xE0 | (cp >> 12)));
    out.push_back(static_cast<char>(0x80 | ((cp >> 6) & 0x3F)));
    out.push_back(static_cast<char>(0x80 | (cp & 0x3F)));
  } else {
    out.push_back(static_cast<char>(0xF0 | (cp >> 18)));
    out.push_back(static_cast<char>(0x80 | ((cp >> 12) & 0x3F)));
    out.push_back(static_cast<char>(0x80 | ((cp >> 6) & 0x3F)));
    out.push_back(static_cast<char>(0x80 | (cp & 0x3F)));
  }
  return true;
}

// Decodes the entity references of an attribute value.
std::optional<std::string> DecodeEntities(absl::string_view raw) {
  std::string out;
  out.reserve(raw.size());
  for (size_t i = 0; i < raw.size(); ++i) {
    if (raw[i] != '&') {
      out.push_back(raw[i]);
      continue;
    }
    const size_t semi = raw.find(';', i);
    if (semi == absl::string_view::npos) return std::nullopt;
    const absl::string_view ref = raw.substr(i + 1, semi - i - 1);
    i = semi;
    if (ref == "amp") {
      out.push_back('&');
    } else if (ref == "lt") {
      out.push_back('<');
    } else if (ref == "gt") {
      out.push_back('>');
    } else if (ref == "quot") {
      out.push_back('"');
    } else if (ref == "apos") {
      out.push_back('\'');
    } else if (ref.size() >= 2 && ref[0] == '#') {
      const bool hex = ref[1] == 'x' || ref[1] == 'X';
      const absl::string_view digits = ref.substr(hex ? 2 : 1);
      uint32_t cp = 0;
      if (digits.empty() || digits.size() > 8) return std::nullopt;
      const bool ok = hex ? absl::SimpleHexAtoi(digits, &cp) : absl::SimpleAtoi(digits, &cp);
      if (!ok || !AppendUtf8(cp, out)) return std::nullopt;
    } else {
      return std::nullopt;
    }
  }
  return out;
}

class Parser {
 public:
  Parser(absl::string_view text, const XmlOptions& options) : text_(text), options_(options) {}

  absl::StatusOr<XmlElement> Parse() {
    if (text_.substr(0, 3) == "\xEF\xBB\xBF") pos_ = 3;  // UTF-8 byte order mark
    std::vector<XmlElement> open;  // the elements not closed yet, outermost first
    std::optional<XmlElement> root;
    while (true) {
      const size_t lt = text_.find('<', pos_);
      if (lt == absl::string_view::npos) break;
      if (open.empty() && !IsBlank(text_.substr(pos_, lt - pos_))) {
        return Error(pos_, "text outside the root element");
      }
      pos_ = lt;
      const absl::string_view rest = text_.substr(pos_);
      if (rest.substr(0, 4) == "<!--") {
        if (absl::Status s = SkipPast("-->", "comment"); !s.ok()) return s;
      } else if (rest.substr(0, 2) == "<?") {
        if (absl::Status s = SkipPast("?>", "processing instruction"); !s.ok()) return s;
      } else if (rest.substr(0, 9) == "<![CDATA[") {
        if (open.empty()) return Error(pos_, "CDATA outside the root element");
        if (absl::Status s = SkipPast("]]>", "CDATA section"); !s.ok()) return s;
      } else if (rest.substr(0, 2) == "<!") {
        if (absl::Status s = SkipDoctype(); !s.ok()) return s;
      } else if (rest.substr(0, 2) == "</") {
        const size_t start = pos_;
        pos_ += 2;
        const absl::string_view name = ReadName();
        SkipSpace();
        if (pos_ >= text_.size() || text_[pos_] != '>') {
          return Error(start, "malformed closing tag");
        }
        ++pos_;
        if (open.empty()) return Error(start, absl::StrCat("unexpected </", name, ">"));
        if (name != open.back().name) {
          return Error(start, absl::StrCat("</", name, "> closes <", open.back().name,
                                           "> (opened on line ", open.back().line, ")"));
        }
        XmlElement done = std::move(open.back());
        open.pop_back();
        if (open.empty()) {
          root = std::move(done);
        } else {
          open.back().children.push_back(std::move(done));
        }
      } else {
        if (root.has_value() && open.empty()) return Error(pos_, "a second root element");
        if (static_cast<int>(open.size()) >= options_.max_depth) {
          return Error(pos_, absl::StrCat("elements nested deeper than ", options_.max_depth));
        }
        bool self_closing = false;
        absl::StatusOr<XmlElement> element = ReadStartTag(&self_closing);
        if (!element.ok()) return element.status();
        if (!self_closing) {
          open.push_back(*std::move(element));
        } else if (open.empty()) {
          root = *std::move(element);
        } else {
          open.back().children.push_back(*std::move(element));
        }
      }
    }
    if (!open.empty()) {
      return Error(text_.size(), absl::StrCat("end of input inside <", open.back().name,
                                              "> (opened on line ", open.back().line, ")"));
    }
    if (!IsBlank(text_.substr(pos_))) return Error(pos_, "text outside the root element");
    if (!root.has_value()) return Error(text_.size(), "no root element");
    return *std::move(root);
  }

 private:
  static bool IsBlank(absl::string_view s) {
    for (char c : s) {
      if (!absl::ascii_isspace(static_cast<unsigned char>(c))) return false;
    }
    return true;
  }

  int LineOf(size_t offset) {
    // Incremental: offsets asked for only grow, except for error reports.
    if (offset < line_offset_) {
      line_offset_ = 0;
      line_ = 1;
    }
    for (; line_offset_ < offset && line_offset_ < text_.size(); ++line_offset_) {
      if (text_[line_offset_] == '\n') ++line_;
    }
    return line_;
  }

  absl::Status Error(size_t offset, absl::string_view what) {
    return absl::InvalidArgumentError(absl::StrCat("line ", LineOf(offset), ": ", what));
  }

  absl::Status SkipPast(absl::string_view terminator, absl::string_view what) {
    const size_t end = text_.find(terminator, pos_);
    if (end == absl::string_view::npos) return Error(pos_, absl::StrCat("unterminated ", what));
    pos_ = end + terminator.size();
    return absl::OkStatus();
  }

  // <!DOCTYPE name ...> with an optional [internal subset] (skipped unread).
  absl::Status SkipDoctype() {
    const size_t start = pos_;
    char quote = 0;
    int brackets = 0;
    for (size_t i = pos_ + 2; i < text_.size(); ++i) {
      const char c = text_[i];
      if (quote != 0) {
        if (c == quote) quote = 0;
      } else if (c == '"' || c == '\'') {
        quote = c;
      } else if (c == '[') {
        ++brackets;
      } else if (c == ']') {
        --brackets;
      } else if (c == '>' && brackets <= 0) {
        pos_ = i + 1;
        return absl::OkStatus();
      }
    }
    return Error(start, "unterminated <! declaration");
  }

  void SkipSpace() {
    while (pos_ < text_.size() && absl::ascii_isspace(static_cast<unsigned char>(text_[pos_]))) {
      ++pos_;
    }
  }

  absl::string_view ReadName() {
    const size_t start = pos_;
    while (pos_ < text_.size() && IsNameChar(text_[pos_])) ++pos_;
    return text_.substr(start, pos_ - start);
  }

  // At '<' of a start tag; leaves pos_ after its '>'.
  absl::StatusOr<XmlElement> ReadStartTag(bool* self_closing) {
    const size_t start = pos_;
    XmlElement element;
    element.line = LineOf(start);
    ++pos_;
    element.name = std::string(ReadName());
    if (element.name.empty()) return Error(start, "'<' not followed by an element name");
    while (true) {
      const size_t before = pos_;
      SkipSpace();
      if (pos_ >= text_.size()) {
        return Error(start, absl::StrCat("unterminated start tag <", element.name));
      }
      if (text_[pos_] == '>') {
        ++pos_;
        *self_closing = false;
        return element;
      }
      if (text_.substr(pos_, 2) == "/>") {
        pos_ += 2;
        *self_closing = true;
        return element;
      }
      if (pos_ == before) {
        return Error(pos_, absl::StrCat("expected space before an attribute in <", element.name));
      }
      const absl::string_view key = ReadName();
      if (key.empty()) {
        return Error(pos_, absl::StrCat("unexpected character '", text_.substr(pos_, 1),
                                        "' in <", element.name));
      }
      SkipSpace();
      if (pos_ >= text_.size() || text_[pos_] != '=') {
        return Error(pos_, absl::StrCat("attribute ", key, " of <", element.name,
                                        "> has no '=value'"));
      }
      ++pos_;
      SkipSpace();
      if (pos_ >= text_.size() || (text_[pos_] != '"' && text_[pos_] != '\'')) {
        return Error(pos_, absl::StrCat("attribute ", key, " of <", element.name,
                                        ">: value not quoted"));
      }
      const char quote = text_[pos_++];
      const size_t end = text_.find(quote, pos_);
      if (end == absl::string_view::npos) {
        return Error(pos_, absl::StrCat("attribute ", key, " of <", element.name,
                                        ">: unterminated value"));
      }
      const absl::string_view raw = text_.substr(pos_, end - pos_);
      pos_ = end + 1;
      if (raw.find('<') != absl::string_view::npos) {
        return Error(pos_, absl::StrCat("attribute ", key, " of <", element.name,
                                        ">: '<' in value"));
      }
      std::optional<std::string> value = DecodeEntities(raw);
      if (!value.has_value()) {
        return Error(pos_, absl::StrCat("attribute ", key, " of <", element.name,
                                        ">: bad entity reference"));
      }
      if (element.Attribute(key) != nullptr) {
        return Error(pos_, absl::StrCat("attribute ", key, " repeated in <", element.name, ">"));
      }
      element.attributes.emplace_back(std::string(key), *std::move(value));
    }
  }

  absl::string_view text_;
  XmlOptions options_;
  size_t pos_ = 0;
  size_t line_offset_ = 0;
  int line_ = 1;
};

}  // namespace

const std::string* XmlElement::Attribute(absl::string_view key) const {
  for (const auto& [k, v] : attributes) {
    if (k == key) return &v;
  }
  return nullptr;
}

absl::StatusOr<XmlElement> ParseXml(absl::string_view text, const XmlOptions& options) {
  return Parser(text, options).Parse();
}

}  // namespace scenes
}  // namespace kdtree
