#include "cc/kdtree/binned_sah.h"

#include <vector>

#include "gtest/gtest.h"

namespace kdtree {
namespace {

TEST(BinnedSah, BinOfClampsAndIsEqualWidth) {
  EXPECT_EQ(BinOf(0.0f, 0.0f, 10.0f, 10), 0);
  EXPECT_EQ(BinOf(0.99f, 0.0f, 10.0f, 10), 0);
  EXPECT_EQ(BinOf(1.0f, 0.0f, 10.0f, 10), 1);
  EXPECT_EQ(BinOf(10.0f, 0.0f, 10.0f, 10), 9);  // the box's end is clamped into the last bin
  EXPECT_EQ(BinOf(-3.0f, 0.0f, 10.0f, 10), 0);  // a reference sticking out of the node
  EXPECT_EQ(BinOf(42.0f, 0.0f, 10.0f, 10), 9);
  EXPECT_FLOAT_EQ(BinPlane(0.0f, 10.0f, 3, 10), 3.0f);
}

TEST(BinnedSah, FirstStrictMinimumWins) {
  // Two unit boxes at both ends of [0, 10]: planes 2..9 all cost
  // SA_L + SA_R = 44 (counted by hand: SA of a 1x1xL box is 4L + 2); plane 1
  // costs 6 * 1 + 38 * 2 = 82. The first strict minimum is plane 2.
  std::vector<BuildRef> refs = {{AABB({0, 0, 0}, {1, 1, 1}), 0}, {AABB({9, 0, 0}, {10, 1, 1}), 1}};
  Config c;
  c.bins = 10;
  c.use_driving_axis = true;
  BinScratch scratch;
  const Split s = FindBinnedSahSplit(refs.data(), refs.size(), AABB({0, 0, 0}, {10, 1, 1}), c, &scratch);
  ASSERT_TRUE(s.found);
  EXPECT_EQ(s.axis, 0);
  EXPECT_FLOAT_EQ(s.pos, 2.0f);
  EXPECT_FLOAT_EQ(s.cost, 44.0f);
}

TEST(BinnedSah, AllAxesFindsTheSeparatingAxis) {
  // x is the longest axis, but only y separates the two groups.
  std::vector<BuildRef> refs;
  for (int i = 0; i < 4; ++i) refs.push_back({AABB({0, 0, 0}, {10, 1, 1}), uint32_t(i)});
  for (int i = 0; i < 4; ++i) refs.push_back({AABB({0, 7, 0}, {10, 8, 1}), uint32_t(4 + i)});
  const AABB node({0, 0, 0}, {10, 8, 1});
  Config c;
  c.bins = 8;
  BinScratch scratch;
  c.use_driving_axis = false;
  const Split all = FindBinnedSahSplit(refs.data(), refs.size(), node, c, &scratch);
  ASSERT_TRUE(all.found);
  EXPECT_EQ(all.axis, 1);
  EXPECT_GE(all.pos, 1.0f);
  EXPECT_LE(all.pos, 7.0f);
  c.use_driving_axis = true;
  const Split driving = FindBinnedSahSplit(refs.data(), refs.size(), node, c, &scratch);
  ASSERT_TRUE(driving.found);
  EXPECT_EQ(driving.axis, 0);
  EXPECT_LT(all.cost, driving.cost);
}

TEST(BinnedSah, FlatAxisIsSkippedAndAPointNodeHasNoSplit) {
  std::vector<BuildRef> refs = {{AABB({1, 1, 1}, {1, 1, 1}), 0}, {AABB({1, 1, 1}, {1, 1, 1}), 1}};
  Config c;
  c.use_driving_axis = false;
  BinScratch scratch;
  EXPECT_FALSE(FindBinnedSahSplit(refs.data(), 2, AABB({1, 1, 1}, {1, 1, 1}), c, &scratch).found);
}

}  // namespace
}  // namespace kdtree
