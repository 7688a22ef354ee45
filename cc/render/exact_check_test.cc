#include "cc/render/exact_check.h"

#include <cmath>
#include <random>

#include "cc/geometry/float_bits.h"
#include "gtest/gtest.h"

namespace kdtree {
namespace {

TEST(ExactCheck, EdgesAreInclusiveAndOneUlpOutsideIsOutside) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  Ray ray;
  ray.dir = Vec3(0, 0, -1);
  ray.origin = Vec3(0.5f, 0.5f, 1);  // exactly on the edge bc (x + y = 1)
  ExactTriangleHit e = ExactIntersect(ray, a, b, c);
  EXPECT_TRUE(e.hit);
  EXPECT_TRUE(e.on_edge);
  EXPECT_EQ(e.t, 1.0);
  EXPECT_EQ(e.edge_distance, 0.0);
  ray.origin = Vec3(NextFloatUp(0.5f), 0.5f, 1);
  e = ExactIntersect(ray, a, b, c);
  EXPECT_FALSE(e.hit);
  EXPECT_FALSE(e.on_edge);
  EXPECT_NEAR(e.edge_distance, std::sqrt(0.5) * std::ldexp(1.0, -24), 1e-12);
  ray.origin = Vec3(NextFloatDown(0.5f), 0.5f, 1);
  EXPECT_TRUE(ExactIntersect(ray, a, b, c).hit);
}

TEST(ExactCheck, TRangeIsOpenBelowAndClosedAbove) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  Ray ray;
  ray.origin = Vec3(0.25f, 0.25f, 1);
  ray.dir = Vec3(0, 0, -1);
  ray.tmax = 1.0f;
  EXPECT_TRUE(ExactIntersect(ray, a, b, c).hit);
  ray.tmax = NextFloatDown(1.0f);
  EXPECT_FALSE(ExactIntersect(ray, a, b, c).hit);
  ray.tmax = 2.0f;
  ray.tmin = 1.0f;
  EXPECT_FALSE(ExactIntersect(ray, a, b, c).hit);
  ray.tmin = NextFloatDown(1.0f);
  EXPECT_TRUE(ExactIntersect(ray, a, b, c).hit);
  ray.dir = Vec3(0, 0, 1);  // away from the triangle: t = -1
  ray.tmin = 0.0f;
  EXPECT_FALSE(ExactIntersect(ray, a, b, c).hit);
}

// The distance is measured across the ray: a ray at a grazing angle passing
// 1e-3 beside an edge is 1e-3 from it, though its hit point on the plane is
// far from the edge.
TEST(ExactCheck, EdgeDistanceIsMeasuredAcrossTheRay) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  Ray ray;
  ray.origin = Vec3(0.25f, -1e-3f, 1);
  ray.dir = Vec3(0, 0, -1);
  ExactTriangleHit e = ExactIntersect(ray, a, b, c);
  EXPECT_FALSE(e.hit);
  EXPECT_NEAR(e.edge_distance, 1e-3, 1e-9);
  ray.origin = Vec3(0.25f, -1e-3f, 0);
  ray.dir = Vec3(0, 1, -1e-3f);  // nearly in the plane, crossing the edge y = 0
  e = ExactIntersect(ray, a, b, c);
  EXPECT_FALSE(e.hit);  // reaches z = 0 only at t = 0: it starts there, tmin is open
  EXPECT_LT(e.edge_distance, 1e-5);
  EXPECT_EQ(e.magnitude, 1.0);
}

TEST(ExactCheck, FloatUlp) {
  EXPECT_EQ(FloatUlp(1.0), std::ldexp(1.0, -23));
  EXPECT_EQ(FloatUlp(1.5), std::ldexp(1.0, -23));
  EXPECT_EQ(FloatUlp(2.0), std::ldexp(1.0, -22));
  EXPECT_EQ(FloatUlp(224.0), std::ldexp(1.0, -16));
  EXPECT_EQ(FloatUlp(0.0), 0.0);
}

}  // namespace
}  // namespace kdtree
