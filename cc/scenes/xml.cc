#include "cc/scenes/xml.h"

#include <algorithm>
#include <cstddef>
#include <vector>

#include "absl/strings/str_cat.h"
#include "pugixml.hpp"

namespace kdtree {
namespace scenes {
namespace {

// 1-based line of byte `offset` of the text (offsets of pugixml's in-place
// parse are those of the input: UTF-8 is not converted).
class Lines {
 public:
  explicit Lines(absl::string_view text) {
    for (size_t i = 0; i < text.size(); ++i) {
      if (text[i] == '\n') newlines_.push_back(i);
    }
  }
  int At(ptrdiff_t offset) const {
    if (offset < 0) return 0;
    return 1 + static_cast<int>(std::lower_bound(newlines_.begin(), newlines_.end(),
                                                 static_cast<size_t>(offset)) -
                                newlines_.begin());
  }

 private:
  std::vector<size_t> newlines_;
};

absl::Status Error(int line, absl::string_view what) {
  return absl::InvalidArgumentError(absl::StrCat("line ", line, ": ", what));
}

// Copies pugixml's element (and its element children, depth levels down)
// into *out.
absl::Status Copy(const pugi::xml_node& node, const Lines& lines, int depth,
                  const XmlOptions& options, XmlElement* out) {
  // offset_debug() is the offset of the name, just past '<'.
  out->line = lines.At(node.offset_debug() - 1);
  if (depth > options.max_depth) {
    return Error(out->line, absl::StrCat("elements nested deeper than ", options.max_depth));
  }
  out->name = node.name();
  for (const pugi::xml_attribute& a : node.attributes()) {
    if (out->Attribute(a.name()) != nullptr) {
      return Error(out->line, absl::StrCat("attribute ", a.name(), " repeated"));
    }
    out->attributes.emplace_back(a.name(), a.value());
  }
  for (const pugi::xml_node& child : node.children()) {
    if (child.type() != pugi::node_element) continue;
    out->children.emplace_back();
    absl::Status st = Copy(child, lines, depth + 1, options, &out->children.back());
    if (!st.ok()) return st;
  }
  return absl::OkStatus();
}

}  // namespace

const std::string* XmlElement::Attribute(absl::string_view key) const {
  for (const auto& [k, v] : attributes) {
    if (k == key) return &v;
  }
  return nullptr;
}

absl::StatusOr<XmlElement> ParseXml(absl::string_view text, const XmlOptions& options) {
  const Lines lines(text);
  pugi::xml_document doc;
  // The default options: CDATA kept as text, entity and character references
  // decoded, line ends normalised; comments, processing instructions and the
  // DOCTYPE (with its internal subset) skipped.
  const pugi::xml_parse_result result =
      doc.load_buffer(text.data(), text.size(), pugi::parse_default, pugi::encoding_utf8);
  if (!result) {
    if (result.status == pugi::status_no_document_element) return Error(1, "no root element");
    return Error(lines.At(result.offset), result.description());
  }
  pugi::xml_node root;
  for (const pugi::xml_node& node : doc.children()) {
    if (node.type() != pugi::node_element) continue;
    if (root) return Error(lines.At(node.offset_debug() - 1), "a second root element");
    root = node;
  }
  if (!root) return Error(1, "no root element");
  XmlElement out;
  absl::Status st = Copy(root, lines, 1, options, &out);
  if (!st.ok()) return st;
  return out;
}

}  // namespace scenes
}  // namespace kdtree
