#include "cc/kdtree/ref_pool.h"

#include "gtest/gtest.h"

namespace kdtree {
namespace {

BuildRef Ref(uint32_t i) {
  const float f = static_cast<float>(i);
  return BuildRef{AABB(Vec3(f, f + 1, f + 2), Vec3(f + 3, f + 4, f + 5)), i};
}

void ExpectRefs(RefPool& pool, size_t n) {
  ASSERT_EQ(pool.size(), n);
  for (size_t i = 0; i < n; ++i) {
    ASSERT_EQ(pool[i].tri, i);
    ASSERT_EQ(pool[i].box.lo.x, static_cast<float>(i));
    ASSERT_EQ(pool[i].box.hi.z, static_cast<float>(i) + 5);
  }
}

TEST(RefPool, GrowingKeepsSizeAndContents) {
  RefPool pool;
  EXPECT_EQ(pool.size(), 0u);
  for (uint32_t i = 0; i < 1000; ++i) {
    const BuildRef r = Ref(i);
    pool.Append(&r, 1);  // grows one reference at a time
  }
  ExpectRefs(pool, 1000);
  // Far beyond the capacity, and beyond a huge page (2 MiB / 28 bytes).
  pool.Reserve(200000);
  EXPECT_GE(pool.capacity(), 200000u);
  ExpectRefs(pool, 1000);
}

TEST(RefPool, ReservedSlotsCommitOnResize) {
  RefPool pool;
  pool.Reserve(4);
  BuildRef* slots = pool.Reserved(100000);  // grows: slots past the end
  EXPECT_EQ(pool.size(), 0u);
  for (uint32_t i = 0; i < 100000; ++i) slots[i] = Ref(i);
  pool.Resize(100000);
  ExpectRefs(pool, 100000);
  pool.Resize(10);  // shrink drops the tail
  ExpectRefs(pool, 10);
}

TEST(RefPool, AppendCopiesAfterTheEnd) {
  std::vector<BuildRef> refs;
  for (uint32_t i = 0; i < 50; ++i) refs.push_back(Ref(i));
  RefPool pool;
  pool.Append(refs.data(), 20);
  pool.Append(refs.data() + 20, 30);
  pool.Append(refs.data(), 0);
  ExpectRefs(pool, 50);
}

}  // namespace
}  // namespace kdtree
