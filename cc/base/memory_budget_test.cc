#include "cc/base/memory_budget.h"

#include "gtest/gtest.h"

namespace kdtree {
namespace {

TEST(MemoryBudget, DefaultIsHalfOfPhysicalMemory) {
  ASSERT_GT(PhysicalMemoryBytes(), 0u);
  EXPECT_EQ(DefaultMemoryBudget(), PhysicalMemoryBytes() / 2);
}

TEST(MemoryBudget, SaysWhatARequestNeeds) {
  EXPECT_TRUE(CheckMemoryBudget(100, 100, "x", "y").ok());
  const absl::Status st = CheckMemoryBudget(31'200'000'000, 12'000'000'000, "the render", "--flag");
  EXPECT_EQ(st.code(), absl::StatusCode::kResourceExhausted);
  EXPECT_EQ(st.message(), "the render needs about 31.2 GB, more than the memory budget of 12.0 GB (--flag)");
}

}  // namespace
}  // namespace kdtree
