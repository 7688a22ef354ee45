#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "cc/geometry/aabb.h"
#include "cc/geometry/float_bits.h"
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

// The inline FMin/FMax and NextFloatUp/Down give the libm answers bit for bit
// (signed zeros aside for FMin/FMax, where C leaves the choice open).
TEST(FloatBits, InlineMinMaxAndNextFloatEqualLibm) {
  std::mt19937 rng(5);
  std::vector<float> xs = {0.0f, -0.0f, 1.0f, -1.0f, std::numeric_limits<float>::denorm_min(),
                           -std::numeric_limits<float>::denorm_min(),
                           std::numeric_limits<float>::min(), std::numeric_limits<float>::max(),
                           -std::numeric_limits<float>::max(), INFINITY, -INFINITY, NAN, 3e-39f};
  for (int i = 0; i < 20000; ++i) {
    uint32_t bits = rng();
    float x;
    std::memcpy(&x, &bits, sizeof(x));
    xs.push_back(std::isnan(x) ? NAN : x);  // glibc answers NaN for signalling NaNs
  }
  auto same = [](float a, float b) {
    return (std::isnan(a) && std::isnan(b)) || (a == b && (a != 0.0f || std::signbit(a) == std::signbit(b)));
  };
  for (size_t i = 0; i < xs.size(); ++i) {
    const float x = xs[i];
    ASSERT_TRUE(same(NextFloatUp(x), std::isinf(x) && x > 0 ? x : std::nextafter(x, INFINITY))) << x;
    ASSERT_TRUE(same(NextFloatDown(x), std::isinf(x) && x < 0 ? x : std::nextafter(x, -INFINITY))) << x;
    const float y = xs[(i * 7919) % xs.size()];
    if (x == 0.0f && y == 0.0f) continue;
    ASSERT_TRUE(same(FMin(x, y), std::fmin(x, y))) << x << " " << y;
    ASSERT_TRUE(same(FMax(x, y), std::fmax(x, y))) << x << " " << y;
  }
}

}  // namespace
}  // namespace kdtree
