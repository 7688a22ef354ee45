#include "cc/scenes/xml.h"

#include <string>

#include "absl/strings/match.h"
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
}

TEST(Xml, ErrorsGiveTheLine) {
  struct Case {
    const char* text;
    const char* error;
  } cases[] = {
      {"", "line 1: no root element"},
      {"<a>\n<b>\n</a>", "line 3: </a> closes <b> (opened on line 2)"},
      {"<a>\n<b>", "end of input inside <b>"},
      {"<a x=1/>", "value not quoted"},
      {"<a x=\"1/>", "unterminated value"},
      {"<a x=\"1\" x=\"2\"/>", "attribute x repeated"},
      {"<a x=\"&bogus;\"/>", "bad entity reference"},
      {"<a x=\"&#0;\"/>", "bad entity reference"},
      {"<a/><b/>", "a second root element"},
      {"<a/>text", "text outside the root element"},
      {"<a>\n<!-- no end", "line 2: unterminated comment"},
      {"</a>", "unexpected </a>"},
      {"<a x=\"1\"y=\"2\"/>", "expected space before an attribute"},
      {"< a/>", "not followed by an element name"},
      {"<a", "unterminated start tag <a"},
  };
  for (const Case& c : cases) {
    absl::StatusOr<XmlElement> root = ParseXml(c.text);
    ASSERT_FALSE(root.ok()) << c.text;
    EXPECT_TRUE(absl::StrContains(root.status().message(), c.error))
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
