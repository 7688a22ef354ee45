#include "cc/base/huge_pages.h"

#include <cstdint>
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

}  // namespace
}  // namespace kdtree
