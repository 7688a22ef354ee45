#include "cc/kdtree/pruning.h"

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
  // A box 1e-9 away from the vertex: exact float SAT says no overlap, the
  // conservative test keeps it (growing the box by 1e-6 of its size).
  const AABB box({1.000001f, 0, -1}, {2, 1, 1});
  EXPECT_FALSE(TriangleOverlapsBoxFloat(A, B, C, box));
  EXPECT_TRUE(TriangleOverlapsBoxConservative(A, B, C, box));
}

}  // namespace
}  // namespace kdtree
