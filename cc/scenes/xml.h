// SuperTuxKart's scene.xml and node.xml as a tree of elements with their
// attributes, read with pugixml (Debian libpugixml-dev).
//
// Text content (also outside the root element), comments, processing
// instructions (<?xml ...?>) and the DOCTYPE (its internal subset too) are
// dropped. Attribute values have the
// five predefined entities (&amp; &lt; &gt; &quot; &apos;) and numeric
// references (&#65; &#x41;) decoded; other references are kept as written.
// No namespaces, no DTD processing, no external entities.
//
// Malformed input gives InvalidArgumentError with the line number
// ("line 12: ..."): callers prefix the file name. pugixml parses without
// recursion; the copy into XmlElement stops at XmlOptions::max_depth.
#ifndef KDTREE_CC_SCENES_XML_H_
#define KDTREE_CC_SCENES_XML_H_

#include <string>
#include <utility>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"

namespace kdtree {
namespace scenes {

struct XmlElement {
  std::string name;
  // In document order; a repeated attribute is an error.
  std::vector<std::pair<std::string, std::string>> attributes;
  std::vector<XmlElement> children;
  int line = 0;  // 1-based line of the element's '<'

  // The value of attribute `key`, or nullptr when absent.
  const std::string* Attribute(absl::string_view key) const;
};

struct XmlOptions {
  // Deepest element nesting accepted (guards the tree against hostile input).
  int max_depth = 256;
};

// The document's root element.
absl::StatusOr<XmlElement> ParseXml(absl::string_view text, const XmlOptions& options = {});

}  // namespace scenes
}  // namespace kdtree

#endif  // KDTREE_CC_SCENES_XML_H_
