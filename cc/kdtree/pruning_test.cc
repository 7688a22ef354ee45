#include "cc/kdtree/pruning.h"

#include <random>

#include "gtest/gtest.h"

namespace kdtree {
namespace {

bool Both(const Vec3& a, const Vec3& b, const Vec3& c, const AABB& box, bool expect) {
  return TriangleOverlapsBoxFloat(a, b, c, box) == expect &&
         TriangleOverlapsBoxConservative(a, b, c, box) == expect;
}

const Vec3 A(0, 0, 0), B(1, 0, 0), C(0, 1, 0);

TEST(Pruning, InsideAndFarAway) {
  EXPECT_TRUE(Both(A, B, C, AABB({-1, -1, -1}, {2, 2, 2}), true));
  EXPECT_TRUE(Both(A, B, C, AABB({0.1f, 0.1f, -0.1f}, {0.2f, 0.2f, 0.1f}), true));
  EXPECT_TRUE(Both(A, B, C, AABB({5, 5, 5}, {6, 6, 6}), false));
}

TEST(Pruning, BoxesOverlapButTheSurfaceDoesNot) {
  // Beyond the hypotenuse x + y = 1 (an edge-cross-product axis separates).
  EXPECT_TRUE(Both(A, B, C, AABB({0.9f, 0.9f, -1}, {1, 1, 1}), false));
  // Above the triangle's plane (the normal axis separates).
  const Vec3 a(0, 0, 0), b(1, 0, 1), c(0, 1, 1);
  EXPECT_TRUE(Both(a, b, c, AABB({0.8f, 0.0f, 0.0f}, {1.0f, 0.1f, 0.5f}), false));
}

TEST(Pruning, TouchingCountsAsOverlap) {
  EXPECT_TRUE(Both(A, B, C, AABB({1, 0, -1}, {2, 1, 1}), true));    // a vertex
  EXPECT_TRUE(Both(A, B, C, AABB({0, -1, -1}, {1, 0, 1}), true));   // an edge
  EXPECT_TRUE(Both(A, B, C, AABB({0, 0, 0}, {1, 1, 0}), true));     // flat box in its plane
}

TEST(Pruning, ConservativeKeepsAHairlineMiss) {
  // A box about 1e-6 away from the vertex: exact float SAT says no overlap,
  // the conservative test keeps it (growing the box by 1e-6 of the values
  // compared, here 1.5e-6).
  const AABB box({1.000001f, 0, -1}, {2, 1, 1});
  EXPECT_FALSE(TriangleOverlapsBoxFloat(A, B, C, box));
  EXPECT_TRUE(TriangleOverlapsBoxConservative(A, B, C, box));
}

TEST(Pruning, ConservativeGrowthDoesNotDependOnWhereTheBoxSits) {
  // A triangle of size 8 and a box 1/8 beyond its vertex, at the origin and
  // moved by 2^17 (exact in float): a clear miss in both places (the growth
  // was 1e-6 of the coordinates' magnitude, 0.13 at 2^17: kept there).
  for (const float offset : {0.0f, 131072.0f}) {
    const Vec3 o(offset, offset, offset);
    const AABB box(Vec3(8.125f, 0, -1) + o, Vec3(9, 1, 1) + o);
    EXPECT_FALSE(TriangleOverlapsBoxConservative(A * 8.0f + o, B * 8.0f + o, C * 8.0f + o, box))
        << offset;
  }
}

// On small integer coordinates every product and sum of the test is exact in
// float, so the float test is the exact answer, and the conservative test
// (its vertex-in-box exit or its separating-axis path) must give the same on
// every pair: separations are at least 1/2, far beyond its 1e-6 growth.
// The same 2^17 away from the origin (still exact in float): a touching
// triangle is kept there too.
class ConservativeOnIntegers : public ::testing::TestWithParam<float> {};

TEST_P(ConservativeOnIntegers, EqualsExact) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> coord(-8, 8);
  const float offset = GetParam();
  const auto point = [&] {
    return Vec3(static_cast<float>(coord(rng)) + offset, static_cast<float>(coord(rng)) + offset,
                static_cast<float>(coord(rng)) + offset);
  };
  int vertex_inside = 0, overlapping = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 a = point(), b = point(), c = point();
    AABB box;
    box.Extend(point());
    box.Extend(point());
    const bool exact = TriangleOverlapsBoxFloat(a, b, c, box);
    ASSERT_EQ(TriangleOverlapsBoxConservative(a, b, c, box), exact) << i;
    vertex_inside += box.Contains(a) || box.Contains(b) || box.Contains(c);
    overlapping += exact;
  }
  // Both paths of the conservative test were taken.
  EXPECT_GT(vertex_inside, 1000);
  EXPECT_GT(overlapping, vertex_inside + 1000);
}

INSTANTIATE_TEST_SUITE_P(Offsets, ConservativeOnIntegers, ::testing::Values(0.0f, 131072.0f));

}  // namespace
}  // namespace kdtree
