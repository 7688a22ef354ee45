#include "cc/base/block_tokens.h"

#include <string>
#include <vector>

#include "gtest/gtest.h"

namespace kdtree {
namespace {

std::vector<std::string> Texts(const std::vector<BlockToken>& tokens) {
  std::vector<std::string> out;
  for (const BlockToken& t : tokens) out.push_back(t.text);
  return out;
}

TEST(BlockTokens, WordsBracesAndLines) {
  const std::vector<BlockToken> t = TokenizeBlocks("KDTree {\n  maxDepth 24\r\n\tbins\v16 }");
  EXPECT_EQ(Texts(t), (std::vector<std::string>{"KDTree", "{", "maxDepth", "24", "bins", "16", "}"}));
  EXPECT_EQ(t[0].line, 1);
  EXPECT_EQ(t[2].line, 2);
  EXPECT_EQ(t[4].line, 3);
  EXPECT_EQ(t[6].line, 3);
}

TEST(BlockTokens, CommentsEndAWordAndTheLine) {
  const std::vector<BlockToken> t = TokenizeBlocks("a#b c\nd// e {\nf{g}h/i");
  EXPECT_EQ(Texts(t), (std::vector<std::string>{"a", "d", "f", "{", "g", "}", "h/i"}));
  EXPECT_EQ(t[1].line, 2);
  EXPECT_EQ(t[2].line, 3);
}

TEST(BlockTokens, EmptyAndCommentOnly) {
  EXPECT_TRUE(TokenizeBlocks("").empty());
  EXPECT_TRUE(TokenizeBlocks("# only\n// comments\n  \n").empty());
  EXPECT_EQ(Texts(TokenizeBlocks("x/")), (std::vector<std::string>{"x/"}));
}

}  // namespace
}  // namespace kdtree
