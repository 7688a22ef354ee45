#include "cc/render/exact_check.h"

#include <cmath>
#include <random>

#include "cc/geometry/float_bits.h"
#include "gtest/gtest.h"

namespace kdtree {
namespace {

// d . ((p1 - p0) x (q1 - q0)) in 128-bit integers, for coordinates that are
// integers times 2^-10.
int IntTripleSign(const Vec3& d, const Vec3& p1, const Vec3& p0, const Vec3& q1, const Vec3& q0) {
  auto i = [](float x) { return static_cast<__int128>(std::ldexp(static_cast<double>(x), 10)); };
  const __int128 dx = i(d.x), dy = i(d.y), dz = i(d.z);
  const __int128 px = i(p1.x) - i(p0.x), py = i(p1.y) - i(p0.y), pz = i(p1.z) - i(p0.z);
  const __int128 qx = i(q1.x) - i(q0.x), qy = i(q1.y) - i(q0.y), qz = i(q1.z) - i(q0.z);
  const __int128 s = dx * (py * qz - pz * qy) + dy * (pz * qx - px * qz) + dz * (px * qy - py * qx);
  return s > 0 ? 1 : (s < 0 ? -1 : 0);
}

TEST(ExactCheck, TripleSignMatchesIntegerArithmetic) {
  std::mt19937 rng(1);
  std::uniform_int_distribution<int> big(-(1 << 23), 1 << 23), small(-3, 3);
  auto g = [&](int m) { return std::ldexp(static_cast<float>(m), -10); };
  int zeros = 0, wrong_in_double = 0;
  for (int k = 0; k < 20000; ++k) {
    const Vec3 p0(g(big(rng)), g(big(rng)), g(big(rng)));
    const Vec3 q0(g(big(rng)), g(big(rng)), g(big(rng)));
    Vec3 p1(g(big(rng)), g(big(rng)), g(big(rng)));
    Vec3 q1(g(big(rng)), g(big(rng)), g(big(rng)));
    Vec3 d(g(big(rng)), g(big(rng)), g(big(rng)));
    if (k % 2 == 1) {  // nearly coplanar: d = (p1 - p0) + (q1 - q0) + a tiny nudge
      const Vec3 p = p1 - p0, q = q1 - q0;  // exact: coordinates below 2^14 in steps of 2^-10
      d = Vec3(p.x + q.x + g(small(rng)), p.y + q.y + g(small(rng)), p.z + q.z + g(small(rng)));
    }
    const int want = IntTripleSign(d, p1, p0, q1, q0);
    ASSERT_EQ(ExactTripleSign(d, p1, p0, q1, q0), want) << "case " << k;
    zeros += want == 0;
    const double p[3] = {double(p1.x) - p0.x, double(p1.y) - p0.y, double(p1.z) - p0.z};
    const double q[3] = {double(q1.x) - q0.x, double(q1.y) - q0.y, double(q1.z) - q0.z};
    const double s = d.x * (p[1] * q[2] - p[2] * q[1]) + d.y * (p[2] * q[0] - p[0] * q[2]) +
                     d.z * (p[0] * q[1] - p[1] * q[0]);
    wrong_in_double += (s > 0 ? 1 : (s < 0 ? -1 : 0)) != want;
  }
  EXPECT_GT(zeros, 10);  // the exact zeros were really exercised
  EXPECT_GT(wrong_in_double, 0);  // and so were signs that plain double gets wrong
}

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
