#include "cc/base/huge_pages.h"

#include <cstdint>
#include <cstring>
#include <numeric>

#include "gtest/gtest.h"

namespace kdtree {
namespace {

TEST(HugePages, LargeArraysAreHugePageAligned) {
  HugeVector<uint32_t> v(kHugePageBytes / sizeof(uint32_t) + 1);
  EXPECT_EQ(reinterpret_cast<uintptr_t>(v.data()) % kHugePageBytes, 0u);
  std::iota(v.begin(), v.end(), 0u);
  EXPECT_EQ(v.back(), kHugePageBytes / sizeof(uint32_t));
}

TEST(HugePages, SmallArraysUseOrdinaryMemory) {
  HugeVector<double> v = {1.0, 2.0, 3.0};
  v.push_back(4.0);
  EXPECT_EQ(v.size(), 4u);
  EXPECT_EQ(v[3], 4.0);
}

TEST(HugePages, GrowingAcrossTheThresholdKeepsTheContents) {
  HugeVector<uint64_t> v;
  const size_t n = 3 * kHugePageBytes / sizeof(uint64_t);
  for (size_t i = 0; i < n; ++i) v.push_back(i * 7);
  for (size_t i = 0; i < n; i += 4099) ASSERT_EQ(v[i], i * 7);
  v.resize(10);
  v.shrink_to_fit();
  EXPECT_EQ(v[9], 63u);
  HugeVector<uint64_t> w = v;  // copies allocate too
  EXPECT_EQ(w, v);
}

TEST(HugePages, ImpossibleRequestsThrow) {
  HugePageAllocator<uint64_t> a;
  EXPECT_THROW(a.allocate(static_cast<size_t>(-1) / 4), std::bad_alloc);
}

// A block of `pages` huge pages, every byte written (so all of it is kept).
void* Written(size_t pages, int value = 1) {
  void* p = AllocateHugePages(pages * kHugePageBytes);
  std::memset(p, value, pages * kHugePageBytes);
  return p;
}

TEST(HugePages, FreedBlocksAreReusedByRequestsTheyFit) {
  SetHugePageCacheLimit(0);  // start empty
  SetHugePageCacheLimit(64 * kHugePageBytes);
  void* big = Written(3, 7);
  void* small = Written(1);
  FreeHugePages(big, 3 * kHugePageBytes);
  FreeHugePages(small, kHugePageBytes);
  EXPECT_EQ(HugePageCacheBytes(), 4 * kHugePageBytes);
  // Best fit: a one-page request takes the one-page block, not the larger.
  EXPECT_EQ(AllocateHugePages(kHugePageBytes / 2), small);
  // A request larger than every kept block gets fresh memory.
  void* fresh = Written(4);
  EXPECT_NE(fresh, big);
  // A block more than twice the request is left for a larger one.
  void* other = Written(1);
  EXPECT_NE(other, big);
  FreeHugePages(other, kHugePageBytes);
  EXPECT_EQ(AllocateHugePages(2 * kHugePageBytes + 1), big);
  EXPECT_EQ(AllocateHugePages(kHugePageBytes), other);
  EXPECT_EQ(static_cast<char*>(big)[0], 7);  // not zeroed: the same memory
  EXPECT_EQ(HugePageCacheBytes(), 0u);
  FreeHugePages(fresh, 4 * kHugePageBytes);
  FreeHugePages(big, 3 * kHugePageBytes);
  FreeHugePages(small, kHugePageBytes);
  FreeHugePages(other, kHugePageBytes);
  EXPECT_EQ(HugePageCacheBytes(), 9 * kHugePageBytes);
  SetHugePageCacheLimit(DefaultHugePageCacheLimit());
}

TEST(HugePages, TheLimitCountsTheMemoryKept) {
  SetHugePageCacheLimit(0);
  FreeHugePages(Written(2), 2 * kHugePageBytes);
  EXPECT_EQ(HugePageCacheBytes(), 0u);  // limit 0: freed at once
  SetHugePageCacheLimit(3 * kHugePageBytes);
  // Never written: no memory to save, not kept (and not counted).
  FreeHugePages(AllocateHugePages(8 * kHugePageBytes), 8 * kHugePageBytes);
  EXPECT_EQ(HugePageCacheBytes(), 0u);
  void* b = Written(2);
  void* c = Written(2);
  FreeHugePages(b, 2 * kHugePageBytes);
  FreeHugePages(c, 2 * kHugePageBytes);  // would exceed the limit: freed
  EXPECT_EQ(HugePageCacheBytes(), 2 * kHugePageBytes);
  // A large block with one written page counts that page, not its size.
  void* sparse = AllocateHugePages(16 * kHugePageBytes);
  static_cast<char*>(sparse)[0] = 1;
  FreeHugePages(sparse, 16 * kHugePageBytes);
  EXPECT_GT(HugePageCacheBytes(), 2 * kHugePageBytes);
  EXPECT_LE(HugePageCacheBytes(), 3 * kHugePageBytes);
  SetHugePageCacheLimit(kHugePageBytes);  // lowering frees to meet it
  EXPECT_LE(HugePageCacheBytes(), kHugePageBytes);
  SetHugePageCacheLimit(0);
  EXPECT_EQ(HugePageCacheBytes(), 0u);
  SetHugePageCacheLimit(DefaultHugePageCacheLimit());
}

TEST(HugePages, ReusedVectorsStillValueInitialise) {
  SetHugePageCacheLimit(DefaultHugePageCacheLimit());
  const size_t n = 2 * kHugePageBytes / sizeof(uint32_t);
  {
    HugeVector<uint32_t> dirty(n, 0xDEADBEEFu);
  }
  HugeVector<uint32_t> clean(n);  // may get the block just freed
  for (size_t i = 0; i < n; i += 1021) ASSERT_EQ(clean[i], 0u);
}

}  // namespace
}  // namespace kdtree
