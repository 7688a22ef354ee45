#include "cc/base/block_tokens.h"

#include <cctype>

namespace kdtree {
namespace {

bool CommentAt(const std::string& text, size_t i) {
  return text[i] == '#' || (text[i] == '/' && i + 1 < text.size() && text[i + 1] == '/');
}

bool Space(char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; }

}  // namespace

std::vector<BlockToken> TokenizeBlocks(const std::string& text) {
  std::vector<BlockToken> out;
  int line = 1;
  size_t i = 0;
  while (i < text.size()) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      ++i;
    } else if (Space(c)) {
      ++i;
    } else if (CommentAt(text, i)) {
      while (i < text.size() && text[i] != '\n') ++i;
    } else if (c == '{' || c == '}') {
      out.push_back({std::string(1, c), line});
      ++i;
    } else {
      size_t j = i;
      while (j < text.size() && !Space(text[j]) && text[j] != '{' && text[j] != '}' && !CommentAt(text, j)) ++j;
      out.push_back({text.substr(i, j - i), line});
      i = j;
    }
  }
  return out;
}

}  // namespace kdtree
