#include "cc/geometry/spawn.h"

#include <cmath>
#include <random>

#include "cc/geometry/watertight.h"
#include "gtest/gtest.h"

namespace kdtree {
namespace {

TEST(Spawn, HitPointErrorBoundHolds) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0, 1), s(-1, 1);
  for (float scale : {1e-8f, 1e-3f, 1.0f, 1e3f, 1e8f}) {
    for (int i = 0; i < 2000; ++i) {
      const Vec3 base = Vec3(s(rng), s(rng), s(rng)) * scale;
      const float size = scale * std::pow(10.0f, -4 * u(rng));
      const Vec3 a = base + Vec3(s(rng), s(rng), s(rng)) * size;
      const Vec3 b = base + Vec3(s(rng), s(rng), s(rng)) * size;
      const Vec3 c = base + Vec3(s(rng), s(rng), s(rng)) * size;
      float bu = u(rng), bv = u(rng);
      if (bu + bv > 1) bu = 1 - bu, bv = 1 - bv;
      const BoundedPoint p = HitPointWithError(a, b, c, bu, bv);
      for (int k = 0; k < 3; ++k) {
        const long double exact = (long double)a[k] + (long double)bu * ((long double)b[k] - a[k]) +
                                  (long double)bv * ((long double)c[k] - a[k]);
        ASSERT_LE(std::fabs((long double)p.p[k] - exact), (long double)p.error[k])
            << "scale " << scale << " axis " << k;
      }
    }
  }
}

TEST(Spawn, GeometricNormalIsUnitAndZeroWhenDegenerate) {
  const Vec3 n = GeometricNormal({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  EXPECT_EQ(n, Vec3(0, 0, 1));
  EXPECT_EQ(GeometricNormal({0, 0, 0}, {1, 1, 1}, {2, 2, 2}), Vec3(0, 0, 0));
}

TEST(Spawn, ShadowRayLeavesItsTriangleAtEveryScale) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0, 1), s(-1, 1);
  int self_hits = 0, rays = 0;
  for (float scale : {1e-8f, 1e-4f, 1.0f, 1e4f, 1e8f}) {
    for (int i = 0; i < 5000; ++i) {
      const Vec3 base = Vec3(s(rng), s(rng), s(rng)) * scale;
      const float size = scale * std::pow(10.0f, -3 * u(rng));
      const Vec3 a = base + Vec3(s(rng), s(rng), s(rng)) * size;
      const Vec3 b = base + Vec3(s(rng), s(rng), s(rng)) * size;
      const Vec3 c = base + Vec3(s(rng), s(rng), s(rng)) * size;
      const Vec3 n = GeometricNormal(a, b, c);
      if (n == Vec3(0, 0, 0)) continue;
      float bu = u(rng), bv = u(rng);
      if (bu + bv > 1) bu = 1 - bu, bv = 1 - bv;
      const BoundedPoint p = HitPointWithError(a, b, c, bu, bv);
      const Vec3 light = base + Vec3(s(rng), s(rng), s(rng)) * (4 * size);
      const Ray ray = SpawnShadowRay(p, n, light);
      float t, hu, hv;
      ++rays;
      self_hits += IntersectTriangleWatertight(MakeWatertightRay(ray), a, b, c, ray.tmin,
                                               ray.tmax, &t, &hu, &hv);
    }
  }
  EXPECT_EQ(self_hits, 0) << "of " << rays;
}

TEST(Spawn, OffsetIsTinyAndOnTheRightSide) {
  const Vec3 a(0.1f, 0, 0), b(1, 0.1f, 0.3f), c(0, 1, 0.7f);
  const BoundedPoint p = HitPointWithError(a, b, c, 0.25f, 0.25f);
  const Vec3 n = GeometricNormal(a, b, c);
  auto side = [&](const Vec3& x) {  // sign of the exact plane equation, in long double
    using LD = long double;
    const LD e1[3] = {LD(b.x) - a.x, LD(b.y) - a.y, LD(b.z) - a.z};
    const LD e2[3] = {LD(c.x) - a.x, LD(c.y) - a.y, LD(c.z) - a.z};
    const long double m[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                              e1[0] * e2[1] - e1[1] * e2[0]};
    return m[0] * ((long double)x.x - a.x) + m[1] * ((long double)x.y - a.y) +
           m[2] * ((long double)x.z - a.z);
  };
  const Vec3 up = OffsetRayOrigin(p, n, n);
  const Vec3 down = OffsetRayOrigin(p, n, -n);
  EXPECT_GT(side(up), 0);
  EXPECT_LT(side(down), 0);
  EXPECT_LT(Length(up - p.p), 1e-6f);
  const Ray shadow = SpawnShadowRay(p, n, p.p - n * 3.0f);
  EXPECT_LT(side(shadow.origin), 0);
  EXPECT_EQ(shadow.tmax, 1.0f);
}

TEST(Spawn, ExactPointOnAnAxisPlaneNeedsNoOffset) {
  // Every coordinate exact (error 0): the origin stays on the plane, and the
  // watertight test's t > 0 rule alone keeps the ray from re-hitting.
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  const BoundedPoint p = HitPointWithError(a, b, c, 0.25f, 0.25f);
  EXPECT_EQ(p.error.z, 0.0f);
  const Ray ray = SpawnShadowRay(p, GeometricNormal(a, b, c), Vec3(0.3f, 0.2f, 5));
  EXPECT_EQ(ray.origin.z, 0.0f);
  float t, u, v;
  EXPECT_FALSE(IntersectTriangleWatertight(MakeWatertightRay(ray), a, b, c, ray.tmin, ray.tmax,
                                           &t, &u, &v));
}

}  // namespace
}  // namespace kdtree
