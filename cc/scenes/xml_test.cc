#include "cc/scenes/xml.h"

#include <string>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "gtest/gtest.h"

namespace kdtree {
namespace scenes {
namespace {

TEST(Xml, ParsesNestedElementsAndAttributes) {
  const std::string text =
      "\xEF\xBB\xBF<?xml version=\"1.0\"?>\n"
      "<!-- Generated with script -->\n"
      "<!DOCTYPE scene [ <!ENTITY x \"y\"> ]>\n"
      "<scene>\n"
      "  <lod>\n"
      "   <group name=\"g\"><static-object model='a.spm' xyz=\"1 2 3\"/></group>\n"
      "  </lod>\n"
      "  some text, ignored <![CDATA[ <not> an element ]]>\n"
      "  <track model=\"t.spm\" x = \"0\" >\n"
      "  </track>\n"
      "</scene>\n"
      "<!-- trailing comment -->\n";
  absl::StatusOr<XmlElement> root = ParseXml(text);
  ASSERT_TRUE(root.ok()) << root.status();
  EXPECT_EQ(root->name, "scene");
  EXPECT_EQ(root->line, 4);
  ASSERT_EQ(root->children.size(), 2u);
  const XmlElement& group = root->children[0].children.at(0);
  EXPECT_EQ(group.name, "group");
  EXPECT_EQ(*group.Attribute("name"), "g");
  const XmlElement& object = group.children.at(0);
  EXPECT_EQ(object.name, "static-object");
  EXPECT_EQ(object.line, 6);
  EXPECT_EQ(*object.Attribute("model"), "a.spm");
  EXPECT_EQ(*object.Attribute("xyz"), "1 2 3");
  EXPECT_EQ(object.Attribute("hpr"), nullptr);
  EXPECT_EQ(*root->children[1].Attribute("x"), "0");
}

TEST(Xml, DecodesEntities) {
  absl::StatusOr<XmlElement> root =
      ParseXml("<a v=\"&lt;&amp;&gt;&quot;&apos;&#65;&#x42;&#xe9;\"/>");
  ASSERT_TRUE(root.ok()) << root.status();
  EXPECT_EQ(*root->Attribute("v"), "<&>\"'AB\xC3\xA9");
  // pugixml keeps a reference it does not know as written.
  root = ParseXml("<a v=\"&bogus;\"/>");
  ASSERT_TRUE(root.ok()) << root.status();
  EXPECT_EQ(*root->Attribute("v"), "&bogus;");
}

// Malformed input fails with "line N: why" (pugixml's reason, or ours for
// what pugixml accepts: a repeated attribute, a second root element,
// nesting too deep). Text outside the root element is ignored, as pugixml
// does.
TEST(Xml, ErrorsGiveTheLine) {
  struct Case {
    const char* text;
    int line;
    const char* error;  // nullptr: pugixml's words
  } cases[] = {
      {"", 1, "no root element"},
      {"<?xml version=\"1.0\"?>\n<!-- only a comment -->", 1, "no root element"},
      {"<a>\n<b>\n</a>", 3, nullptr},
      {"<a>\n<b>", 2, nullptr},
      {"<a x=1/>", 1, nullptr},
      {"<a\n x=\"1/>", 2, nullptr},
      {"<a>\n<b x=\"1\" x=\"2\"/></a>", 2, "attribute x repeated"},
      {"<a/>\n<b/>", 2, "a second root element"},
      {"<a>\n<!-- no end", 2, nullptr},
      {"</a>", 1, nullptr},
      {"< a/>", 1, nullptr},
      {"<a", 1, nullptr},
  };
  for (const Case& c : cases) {
    absl::StatusOr<XmlElement> root = ParseXml(c.text);
    ASSERT_FALSE(root.ok()) << c.text;
    const std::string want = absl::StrCat("line ", c.line, ": ", c.error ? c.error : "");
    EXPECT_TRUE(absl::StartsWith(root.status().message(), want))
        << c.text << " -> " << root.status();
  }
}

TEST(Xml, DepthIsBounded) {
  std::string deep;
  for (int i = 0; i < 100; ++i) deep += "<e>";
  for (int i = 0; i < 100; ++i) deep += "</e>";
  XmlOptions shallow;
  shallow.max_depth = 50;
  EXPECT_TRUE(ParseXml(deep).ok());
  absl::StatusOr<XmlElement> root = ParseXml(deep, shallow);
  ASSERT_FALSE(root.ok());
  EXPECT_TRUE(absl::StrContains(root.status().message(), "nested deeper than 50"));
}

TEST(Xml, EveryPrefixOfADocumentParsesOrFails) {
  const std::string text =
      "<?xml version=\"1.0\"?><scene><object a=\"1\" b='&amp;'><curve/></object>"
      "<!-- c --></scene>";
  for (size_t n = 0; n < text.size(); ++n) {
    EXPECT_FALSE(ParseXml(text.substr(0, n)).ok()) << n;  // never a crash
  }
  EXPECT_TRUE(ParseXml(text).ok());
}

}  // namespace
}  // namespace scenes
}  // namespace kdtree
