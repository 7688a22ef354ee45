#include "cc/base/fnv.h"

#include <string>

#include "gtest/gtest.h"

namespace kdtree {
namespace {

TEST(Fnv, BytesMatchTheReferenceVectors) {
  EXPECT_EQ(FnvBytes("", 0), 0xcbf29ce484222325ull);
  EXPECT_EQ(FnvBytes("a", 1), 0xaf63dc4c8601ec8cull);
  EXPECT_EQ(FnvBytes("foobar", 6), 0x85944171f73967e8ull);
}

TEST(Fnv, WordsAndTheirTwoTails) {
  const std::string s = "0123456789";  // one word and a tail of 2
  uint64_t w0;
  std::memcpy(&w0, s.data(), 8);
  const uint64_t head = (kFnvOffset ^ w0) * kFnvPrime;
  EXPECT_EQ(FnvWords(s.data(), 8), head);
  const uint64_t padded = (head ^ (uint64_t{'9'} << 8 | uint64_t{'8'})) * kFnvPrime;
  EXPECT_EQ(FnvWords(s.data(), 10), padded);
  EXPECT_EQ(FnvWords(s.data(), 10, kFnvOffset, FnvTail::kBytes), FnvBytes(s.data() + 8, 2, head));
  EXPECT_NE(padded, FnvBytes(s.data() + 8, 2, head));
}

}  // namespace
}  // namespace kdtree
