#include "cc/kdtree/binned_sah.h"

#include <algorithm>
#include <random>
#include <vector>

#include "cc/kdtree/sah_cost.h"
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

TEST(BinnedSah, OnePassCountsEqualScalarBinOf) {
  // References inside, straddling, far outside and flat, on a node with a
  // tiny, an ordinary and a zero extent; bins that are and are not powers of 2.
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-2.0f, 3.0f);
  const AABB nodes[] = {AABB({0, 0, 0}, {1, 1, 1}), AABB({0.1f, -1e-6f, 5}, {0.3f, 1e-6f, 5}),
                        AABB({-1e4f, 2, -3}, {1e4f, 2.5f, 7})};
  for (const AABB& node : nodes) {
    for (int bins : {2, 7, 8, 32, 255}) {
      std::vector<BuildRef> refs;
      for (uint32_t i = 0; i < 500; ++i) {
        Vec3 a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng));
        if (i % 5 == 0) b = a;  // a point
        if (i % 7 == 0) a = Vec3(-1e30f, a.y, 1e30f);
        refs.push_back({AABB(Min(a, b), Max(a, b)), i});
      }
      BinScratch s;
      CountBinsAllAxes(refs.data(), refs.size(), node, bins, &s);
      for (int axis = 0; axis < 3; ++axis) {
        const float lo = node.lo[axis], extent = node.hi[axis] - lo;
        if (!(extent > 0.0f)) continue;  // never read
        std::vector<uint32_t> starts(bins), ends(bins);
        for (const BuildRef& r : refs) {
          ++starts[BinOf(r.box.lo[axis], lo, extent, bins)];
          ++ends[BinOf(r.box.hi[axis], lo, extent, bins)];
        }
        for (int i = 0; i < bins; ++i) {
          ASSERT_EQ(s.starts[axis * bins + i], starts[i]) << axis << " " << bins << " " << i;
          ASSERT_EQ(s.ends[axis * bins + i], ends[i]) << axis << " " << bins << " " << i;
        }
      }
    }
  }
}

// The scalar definition: BinOf counts, BinPlane planes, SplitCost costs, the
// first strict minimum over axes 0, 1, 2.
Split ScalarBinnedSah(const std::vector<BuildRef>& refs, const AABB& box, const Config& c) {
  Split best;
  for (int axis = 0; axis < 3; ++axis) {
    const float lo = box.lo[axis], extent = box.hi[axis] - lo;
    if (!(extent > 0.0f)) continue;
    std::vector<uint32_t> starts(c.bins), ends(c.bins);
    for (const BuildRef& r : refs) {
      ++starts[BinOf(r.box.lo[axis], lo, extent, c.bins)];
      ++ends[BinOf(r.box.hi[axis], lo, extent, c.bins)];
    }
    float nl = 0.0f, nr = static_cast<float>(refs.size());
    for (int i = 0; i + 1 < c.bins; ++i) {
      nl += static_cast<float>(starts[i]);
      nr -= static_cast<float>(ends[i]);
      const float plane = BinPlane(lo, extent, i + 1, c.bins);
      const float cost = SplitCost(box, axis, plane, nl, nr, c);
      if (!best.found || cost < best.cost) best = Split{true, axis, plane, cost};
    }
  }
  return best;
}

TEST(BinnedSah, VectorisedSweepIsBitIdenticalToTheScalarDefinition) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-5.0f, 5.0f);
  for (int trial = 0; trial < 300; ++trial) {
    Vec3 a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng));
    if (trial % 10 == 0) b.z = a.z;  // a flat node
    const AABB node(Min(a, b), Max(a, b));
    std::vector<BuildRef> refs;
    const int n = 1 + trial % 37;
    for (int i = 0; i < n; ++i) {
      Vec3 p(u(rng), u(rng), u(rng)), q = p + Vec3(u(rng), u(rng), u(rng)) * 0.2f;
      refs.push_back({AABB(Min(p, q), Max(p, q)), static_cast<uint32_t>(i)});
    }
    for (int bins : {3, 8, 9, 32, 64}) {
      Config c;
      c.bins = bins;
      c.use_driving_axis = false;
      for (bool full : {false, true}) {
        c.full_sah = full;
        BinScratch scratch;
        const Split got = FindBinnedSahSplit(refs.data(), refs.size(), node, c, &scratch);
        const Split want = ScalarBinnedSah(refs, node, c);
        ASSERT_EQ(got.found, want.found);
        if (!want.found) continue;
        ASSERT_EQ(got.axis, want.axis) << trial << " " << bins;
        ASSERT_EQ(got.pos, want.pos) << trial << " " << bins;  // bit-identical
        ASSERT_EQ(got.cost, want.cost) << trial << " " << bins;
      }
    }
  }
}

// Index references (build_ref.h) read their boxes from an array by triangle:
// the same split as BuildRefs holding those boxes, bit for bit, on the driving
// axis and on all three, for references in any order (a child's indices are a
// subsequence of its parent's) and with a box array just long enough.
TEST(BinnedSah, IndexReferencesGiveTheSplitOfBoxReferences) {
  std::mt19937 rng(13);
  std::uniform_real_distribution<float> u(-5.0f, 5.0f);
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 1 + trial % 41;
    std::vector<AABB> boxes;
    for (int i = 0; i < n; ++i) {
      Vec3 p(u(rng), u(rng), u(rng)), q = p + Vec3(u(rng), u(rng), u(rng)) * 0.3f;
      boxes.push_back(AABB(Min(p, q), Max(p, q)));
    }
    AABB node;
    for (const AABB& b : boxes) node.Extend(b);
    boxes.push_back(AABB());  // the one element past the end
    std::vector<IndexRef> index;
    for (int i = 0; i < n; ++i) {
      if ((i * 7 + trial) % 3 != 0 || i == 0) index.push_back(static_cast<IndexRef>(i));
    }
    std::shuffle(index.begin(), index.end(), rng);
    std::vector<BuildRef> refs;
    for (IndexRef t : index) refs.push_back(BuildRef{boxes[t], t});
    for (int bins : {2, 8, 32}) {
      for (bool driving : {true, false}) {
        Config c;
        c.bins = bins;
        c.use_driving_axis = driving;
        BinScratch s1, s2;
        const Split want = FindBinnedSahSplit(refs.data(), refs.size(), node, c, &s1);
        const Split got =
            FindBinnedSahSplit(index.data(), boxes.data(), index.size(), node, c, &s2);
        ASSERT_EQ(got.found, want.found) << trial;
        if (!want.found) continue;
        ASSERT_EQ(got.axis, want.axis) << trial;
        ASSERT_EQ(got.pos, want.pos) << trial;
        ASSERT_EQ(got.cost, want.cost) << trial;
      }
    }
  }
}

}  // namespace
}  // namespace kdtree
