#include <cmath>
#include <limits>

#include "cc/geometry/aabb.h"
#include "cc/geometry/intersect.h"
#include "cc/geometry/triangle.h"
#include "gtest/gtest.h"

namespace kdtree {
namespace {

TEST(AABB, SurfaceAreaOfUnitCubeIsSix) {
  AABB b({0, 0, 0}, {1, 1, 1});
  EXPECT_FLOAT_EQ(b.SurfaceArea(), 6.0f);
  EXPECT_FLOAT_EQ(AABB({0, 0, 0}, {2, 3, 0}).SurfaceArea(), 12.0f);  // flat box
}

TEST(AABB, EmptyIsInvalidAndExtendMakesValid) {
  AABB b;
  EXPECT_FALSE(b.Valid());
  b.Extend(Vec3(1, 2, 3));
  EXPECT_TRUE(b.Valid());
  EXPECT_EQ(b.lo, Vec3(1, 2, 3));
  EXPECT_EQ(b.hi, Vec3(1, 2, 3));
}

TEST(AABB, LongestAxisTiesGoToLowerAxis) {
  EXPECT_EQ(AABB({0, 0, 0}, {1, 1, 1}).LongestAxis(), 0);
  EXPECT_EQ(AABB({0, 0, 0}, {1, 2, 2}).LongestAxis(), 1);
  EXPECT_EQ(AABB({0, 0, 0}, {1, 1, 3}).LongestAxis(), 2);
}

TEST(AABB, SplitAndOverlap) {
  AABB b({0, 0, 0}, {4, 2, 2});
  AABB l = b.LeftOf(0, 1), r = b.RightOf(0, 1);
  EXPECT_EQ(l.hi.x, 1);
  EXPECT_EQ(r.lo.x, 1);
  EXPECT_TRUE(l.Overlaps(r));  // they touch in the plane x = 1
  EXPECT_FALSE(AABB({0, 0, 0}, {1, 1, 1}).Overlaps(AABB({1.5f, 0, 0}, {2, 1, 1})));
  EXPECT_FALSE(Intersect(AABB({0, 0, 0}, {1, 1, 1}), AABB({2, 0, 0}, {3, 1, 1})).Valid());
  EXPECT_TRUE(Intersect(l, r).Valid());
}

TEST(Intersect, HitsInteriorAndReportsT) {
  TriAccel tri = MakeTriAccel({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  Ray ray{{0.25f, 0.25f, 1}, {0, 0, -1}};
  float t, u, v;
  ASSERT_TRUE(IntersectTriangle(ray, tri, 0, 10, &t, &u, &v));
  EXPECT_FLOAT_EQ(t, 1.0f);
  EXPECT_FLOAT_EQ(u, 0.25f);
  EXPECT_FLOAT_EQ(v, 0.25f);
}

TEST(Intersect, MissesOutsideAndBehindAndBeyondTmax) {
  TriAccel tri = MakeTriAccel({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  float t, u, v;
  EXPECT_FALSE(IntersectTriangle({{0.8f, 0.8f, 1}, {0, 0, -1}}, tri, 0, 10, &t, &u, &v));
  EXPECT_FALSE(IntersectTriangle({{0.2f, 0.2f, -1}, {0, 0, -1}}, tri, 0, 10, &t, &u, &v));
  EXPECT_FALSE(IntersectTriangle({{0.2f, 0.2f, 1}, {0, 0, -1}}, tri, 0, 0.5f, &t, &u, &v));
}

TEST(Intersect, ParallelAndNanRaysMiss) {
  TriAccel tri = MakeTriAccel({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  float t, u, v;
  EXPECT_FALSE(IntersectTriangle({{0.2f, 0.2f, 0}, {1, 0, 0}}, tri, 0, 10, &t, &u, &v));
  const float nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_FALSE(IntersectTriangle({{nan, 0.2f, 1}, {0, 0, -1}}, tri, 0, 10, &t, &u, &v));
  EXPECT_FALSE(IntersectTriangle({{0.2f, 0.2f, 1}, {nan, 0, -1}}, tri, 0, 10, &t, &u, &v));
}

TEST(TriangleSoup, BoundsCoverAllVertices) {
  TriangleSoup s;
  s.Add({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  s.Add({-1, 5, 2}, {0, 0, 0}, {0, 0, 3});
  EXPECT_EQ(s.size(), 2u);
  AABB b = s.Bounds();
  EXPECT_EQ(b.lo, Vec3(-1, 0, 0));
  EXPECT_EQ(b.hi, Vec3(1, 5, 3));
  EXPECT_EQ(s.Bounds(1).hi, Vec3(0, 5, 3));
}

}  // namespace
}  // namespace kdtree
