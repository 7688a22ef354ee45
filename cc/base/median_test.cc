#include "cc/base/median.h"

#include "gtest/gtest.h"

namespace kdtree {
namespace {

TEST(Median, OfRuns) {
  EXPECT_EQ(Median({}), 0.0);
  EXPECT_EQ(Median({1.5}), 1.5);
  EXPECT_EQ(Median({3.0, 1.0, 2.0}), 2.0);
  EXPECT_EQ(Median({4.0, 1.0, 3.0, 2.0}), 2.5);
}

}  // namespace
}  // namespace kdtree
