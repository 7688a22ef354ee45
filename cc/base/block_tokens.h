// The tokens of the block syntax shared by environment files (the report's
// configuration syntax, cc/kdtree/env_file.h) and view files
// (cc/render/view.h): `Name { key value ... }`, with comments from `#` or
// `//` to the end of the line.
//
// A token is `{`, `}`, or a word: a run of characters up to whitespace
// (std::isspace), a brace, `#` or `//`. Each carries the line it starts on
// (from 1).
#ifndef KDTREE_CC_BASE_BLOCK_TOKENS_H_
#define KDTREE_CC_BASE_BLOCK_TOKENS_H_

#include <string>
#include <vector>

namespace kdtree {

struct BlockToken {
  std::string text;
  int line = 1;
};

std::vector<BlockToken> TokenizeBlocks(const std::string& text);

}  // namespace kdtree

#endif  // KDTREE_CC_BASE_BLOCK_TOKENS_H_
