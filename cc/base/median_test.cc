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

TEST(Median, PairedAndLessPerRound) {
  // Only the rounds both have.
  EXPECT_EQ(PairedRatios({2.0, 3.0, 9.0}, {1.0, 6.0}), (std::vector<double>{2.0, 0.5}));
  EXPECT_EQ(LessPerRound({2.0, 3.0}, {0.5, 1.0, 7.0}), (std::vector<double>{1.5, 2.0}));
}

}  // namespace
}  // namespace kdtree
