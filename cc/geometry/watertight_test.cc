#include "cc/geometry/watertight.h"

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "cc/geometry/exact_area.h"
#include "cc/geometry/exact_t.h"
#include "cc/geometry/intersect.h"
#include "cc/geometry/ray_check.h"
#include "gtest/gtest.h"

namespace kdtree {
namespace {

bool Hits(const Ray& ray, const Vec3& a, const Vec3& b, const Vec3& c, float* t = nullptr) {
  float tt, u, v;
  const bool hit = IntersectTriangleWatertight(MakeWatertightRay(ray), a, b, c, ray.tmin,
                                               ray.tmax, &tt, &u, &v);
  if (hit && t != nullptr) *t = tt;
  return hit;
}

bool HitsFast(const Ray& ray, const Vec3& a, const Vec3& b, const Vec3& c) {
  float t, u, v;
  return IntersectTriangle(ray, MakeTriAccel(a, b, c), ray.tmin, ray.tmax, &t, &u, &v);
}

TEST(Watertight, HitsLikeMoellerTrumbore) {
  const Vec3 a(-1, -1, 5), b(1, -1, 5), c(0, 1, 5);
  float t, u, v;
  const Ray ray{{0.25f, 0, 0}, {0, 0, 1}};
  ASSERT_TRUE(IntersectTriangleWatertight(MakeWatertightRay(ray), a, b, c, 0, INFINITY, &t, &u,
                                          &v));
  EXPECT_FLOAT_EQ(t, 5.0f);
  float t2, u2, v2;
  ASSERT_TRUE(IntersectTriangle(ray, MakeTriAccel(a, b, c), 0, INFINITY, &t2, &u2, &v2));
  EXPECT_NEAR(u, u2, 1e-6f);
  EXPECT_NEAR(v, v2, 1e-6f);
  // Every dominant axis and both signs (the winding swap for negative ones).
  for (int axis = 0; axis < 3; ++axis) {
    for (float sign : {1.0f, -1.0f}) {
      Vec3 d(0.01f, 0.02f, 0.015f);
      d[axis] = sign;
      Vec3 o(0, 0, 0);
      o[axis] = -10 * sign;
      Vec3 p = Vec3(0, 0, 0), q = p, r = p;
      p[(axis + 1) % 3] = -3, p[(axis + 2) % 3] = -3;
      q[(axis + 1) % 3] = 3, q[(axis + 2) % 3] = -3;
      r[(axis + 2) % 3] = 3;
      EXPECT_TRUE(Hits(Ray{o, d}, p, q, r)) << axis << " " << sign;
      EXPECT_TRUE(Hits(Ray{o, d}, p, r, q)) << axis << " " << sign << " (other winding)";
    }
  }
}

TEST(Watertight, RespectsTheInterval) {
  const Vec3 a(-1, -1, 5), b(1, -1, 5), c(0, 1, 5);
  EXPECT_TRUE(Hits(Ray{{0, 0, 0}, {0, 0, 1}, 0, 5}, a, b, c));    // tmax inclusive
  EXPECT_FALSE(Hits(Ray{{0, 0, 0}, {0, 0, 1}, 0, 4.99f}, a, b, c));
  EXPECT_FALSE(Hits(Ray{{0, 0, 0}, {0, 0, 1}, 5, 6}, a, b, c));    // tmin exclusive
  EXPECT_FALSE(Hits(Ray{{0, 0, 0}, {0, 0, -1}}, a, b, c));         // behind
}

TEST(Watertight, InPlaneAndDegenerateMiss) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  EXPECT_FALSE(Hits(Ray{{-1, 0.25f, 0}, {1, 0, 0}}, a, b, c));  // ray in the plane
  EXPECT_FALSE(Hits(Ray{{0.5f, 0, -1}, {0, 0, 1}}, a, b, Vec3(2, 0, 0)));  // collinear
  EXPECT_FALSE(Hits(Ray{{0, 0, -1}, {0, 0, 1}}, a, a, a));  // a point
}

TEST(Watertight, ZeroAreaTrianglesAreNeverHit) {
  // Exactly collinear (dyadic) vertices: the shear can round them apart into a
  // sliver of nonzero projected area; the exact zero-area test rejects it.
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1, 1);
  int hits = 0, rays = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    auto dyadic = [&] { return std::round(u(rng) * 4096) / 4096; };
    const Vec3 p(dyadic(), dyadic(), dyadic() + 3), d(dyadic() / 4, dyadic() / 4, dyadic() / 4);
    const Vec3 a = p, b = p + d, c = p + d * 2.0f;
    ASSERT_TRUE(HasZeroArea(a, b, c));
    for (const Vec3& target : {b, (a + b) * 0.5f, (b + c) * 0.5f}) {
      const Vec3 origin(u(rng), u(rng), u(rng) - 2);
      ++rays;
      hits += Hits(Ray{origin, target - origin}, a, b, c);
    }
  }
  EXPECT_EQ(hits, 0) << "of " << rays;
  EXPECT_FALSE(HasZeroArea({0, 0, 0}, {1, 0, 0}, {0, 1e-30f, 0}));
}

TEST(Watertight, SharedEdgeIsAlwaysHit) {
  // Two triangles sharing edge p-q; rays through exact points of the edge
  // from generic origins: the watertight test hits one of them every time.
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1, 1);
  int watertight_misses = 0, fast_misses = 0, rays = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3 p(u(rng), u(rng), u(rng) + 3), q(u(rng), u(rng), u(rng) + 3);
    const Vec3 r1(u(rng), u(rng), u(rng) + 3), r2 = p + q - r1;  // opposite side
    for (int k = 1; k < 16; ++k) {  // the end points are corners of the pair, not shared
      const float s = k / 16.0f;
      const Vec3 target = p + (q - p) * s;
      const Vec3 origin(u(rng) * 0.1f, u(rng) * 0.1f, u(rng) * 0.1f);
      const Ray ray{origin, target - origin};
      ++rays;
      watertight_misses += !(Hits(ray, p, q, r1) || Hits(ray, q, p, r2));
      fast_misses += !(HitsFast(ray, p, q, r1) || HitsFast(ray, q, p, r2));
    }
  }
  EXPECT_EQ(watertight_misses, 0) << "of " << rays;
  std::printf("shared edge: %d rays, watertight misses %d, Moeller-Trumbore misses %d\n", rays,
              watertight_misses, fast_misses);
}

TEST(Watertight, SharedVertexOfAFanIsAlwaysHit) {
  // A closed fan of 7 triangles around a vertex; rays aimed exactly at it.
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> u(-1, 1);
  int misses = 0;
  for (int trial = 0; trial < 500; ++trial) {
    const Vec3 centre(u(rng), u(rng), 2 + u(rng));
    std::vector<Vec3> ring;
    for (int i = 0; i < 7; ++i) {
      const float a = 6.2831853f * (i + 0.3f * u(rng)) / 7;
      ring.push_back(centre + Vec3(std::cos(a), std::sin(a), 0.3f * u(rng)));
    }
    const Vec3 origin(u(rng) * 0.5f, u(rng) * 0.5f, u(rng) * 0.5f - 2);
    const Ray ray{origin, centre - origin};
    bool hit = false;
    for (int i = 0; i < 7; ++i) hit = hit || Hits(ray, centre, ring[i], ring[(i + 1) % 7]);
    misses += !hit;
  }
  EXPECT_EQ(misses, 0);
}

TEST(Watertight, HugeAndTinyCoordinates) {
  for (float scale : {1e-30f, 1e-8f, 1.0f, 1e8f, 1e20f, 1e30f}) {
    const Vec3 a = Vec3(-1, -1, 5) * scale, b = Vec3(1, -1, 5) * scale, c = Vec3(0, 1, 5) * scale;
    float t = 0;
    EXPECT_TRUE(Hits(Ray{{0, 0, 0}, {0, 0, 1}}, a, b, c, &t)) << scale;
    EXPECT_FLOAT_EQ(t, 5 * scale) << scale;
    // Edge functions overflow float here for scale >= 1e20: the double
    // fallback still gets the signs and t right.
    EXPECT_TRUE(Hits(Ray{Vec3(0, -1, 0) * scale, {0, 0, 1}}, a, b, c)) << scale << " on the edge";
  }
}

// A ray from a point on the plane up to rounding (well inside the triangle)
// hits it exactly when, in exact arithmetic, the point is on the far side of
// the plane from where the ray goes: the intersector is exact there, and
// keeping a spawned ray off its own surface is spawn.h's job (spawn_test,
// cc/robust case 7). Of two opposite directions at most one hits.
TEST(Watertight, OriginOnTheTriangleHitsAsExactArithmeticSays) {
  const Vec3 a(0.1f, 0.2f, 0.3f), b(7.1f, 0.9f, -0.4f), c(0.3f, 5.7f, 1.3f);
  const Vec3 p = a + (b - a) * 0.3f + (c - a) * 0.3f;  // on the plane up to rounding
  for (const Vec3& d : {Vec3(0.3f, -0.2f, 1), Vec3(1, 1, 1)}) {
    const bool forward = Hits(Ray{p, d}, a, b, c), backward = Hits(Ray{p, -d}, a, b, c);
    EXPECT_EQ(forward, ExactPlaneHitBeyond(p, d, a, b, c, 0.0f));
    EXPECT_EQ(backward, ExactPlaneHitBeyond(p, -d, a, b, c, 0.0f));
    EXPECT_FALSE(forward && backward);
  }
}

// Real shadow rays (stk-ravenbridge-mansion, engine) that cross a large or
// sliver triangle spanning the origin's depth close to the origin: the t
// rounding bound alone would reject them; the exact test keeps them.
TEST(Watertight, CloseOccluderOfALargeTriangleIsHit) {
  Ray r;
  r.origin = Vec3(-171.213486f, 581.384583f, 292.709412f);
  r.dir = Vec3(802.54248f, 989.195374f, 706.55658f);
  r.tmin = 0.0f;
  r.tmax = 1.0f;
  float t = 0;
  EXPECT_TRUE(Hits(r, Vec3(-169.826157f, 583.827637f, 295.357727f),
                   Vec3(-171.152405f, 582.959717f, 292.923798f),
                   Vec3(59.1861801f, 68.3025513f, 353.043121f), &t));
  EXPECT_NEAR(t, 7.205e-4, 0.01e-4);
  Ray e;
  e.origin = Vec3(-224.001053f, 59.2209358f, 74.3958282f);
  e.dir = Vec3(433.014038f, 523.352051f, 337.62915f);
  e.tmin = 0.0f;
  e.tmax = 1.0f;
  EXPECT_TRUE(Hits(e, Vec3(-224.000031f, 53.5317688f, 77.0521545f),
                   Vec3(-224.000046f, 80.7639618f, 53.4683723f),
                   Vec3(-224.000031f, 61.7991104f, 73.1961823f), &t));
  EXPECT_GT(t, 0.0f);
  // The same rays reversed start just in front of the plane and move away: no hit.
  e.dir = -e.dir;
  EXPECT_FALSE(Hits(e, Vec3(-224.000031f, 53.5317688f, 77.0521545f),
                    Vec3(-224.000046f, 80.7639618f, 53.4683723f),
                    Vec3(-224.000031f, 61.7991104f, 73.1961823f)));
}

// exact_t.h on planes where the sign of t is plain, at tmin 0 and beyond.
TEST(ExactT, DecidesTheSideOfTmin) {
  const Vec3 a(0, 0, 1), b(1, 0, 1), c(0, 1, 1);
  EXPECT_TRUE(ExactPlaneHitBeyond(Vec3(0, 0, 0), Vec3(0, 0, 1), a, b, c, 0.0f));
  EXPECT_FALSE(ExactPlaneHitBeyond(Vec3(0, 0, 0), Vec3(0, 0, -1), a, b, c, 0.0f));
  EXPECT_FALSE(ExactPlaneHitBeyond(Vec3(0, 0, 1), Vec3(0, 0, 1), a, b, c, 0.0f));  // t = 0
  EXPECT_TRUE(ExactPlaneHitBeyond(Vec3(0, 0, 0), Vec3(0, 0, 1), a, b, c, 0.999f));
  EXPECT_FALSE(ExactPlaneHitBeyond(Vec3(0, 0, 0), Vec3(0, 0, 1), a, b, c, 1.0f));
  EXPECT_FALSE(ExactPlaneHitBeyond(Vec3(0, 0, 0), Vec3(1, 0, 0), a, b, c, 0.0f));  // parallel
  // An origin one ulp in front of the plane, moving toward it: t > 0.
  const float below = std::nextafter(1.0f, 0.0f);
  EXPECT_TRUE(ExactPlaneHitBeyond(Vec3(0.25f, 0.25f, below), Vec3(0, 0, 1), a, b, c, 0.0f));
}

// The double filter of ExactPlaneHitBeyond decides as the expansions do, on
// origins within rounding of the plane (the filter's hard cases), at scales
// from 1e-6 to 1e6.
TEST(ExactT, FilterAgreesWithExpansions) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), w(0.0f, 1.0f);
  for (float scale : {1e-6f, 1.0f, 1e6f}) {
    for (int i = 0; i < 20000; ++i) {
      const Vec3 a = Vec3(u(rng), u(rng), u(rng)) * scale, b = Vec3(u(rng), u(rng), u(rng)) * scale,
                 c = Vec3(u(rng), u(rng), u(rng)) * scale;
      const float s = w(rng), t = w(rng) * (1 - s);
      const Vec3 o = a + (b - a) * s + (c - a) * t;  // on the plane up to rounding
      const Vec3 d(u(rng), u(rng), u(rng));
      const bool filtered = ExactPlaneHitBeyond(o, d, a, b, c, 0.0f);
      ASSERT_EQ(filtered, exact_t_internal::ExactExpansions(o, d, a, b, c, 0.0f)) << i;
      // Both directions beyond the origin at once is impossible.
      ASSERT_FALSE(filtered && ExactPlaneHitBeyond(o, -d, a, b, c, 0.0f)) << i;
    }
  }
}

// Origins exactly in an axis-aligned plane holding the triangle, or on one of
// its vertices: t = 0 exactly, decided without expansions, as they decide.
TEST(ExactT, OriginInTheTrianglesAxisPlaneIsNotBeyondZero) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (int i = 0; i < 20000; ++i) {
    const float level = u(rng) * 100.0f;
    const int k = i % 3;
    auto on_plane = [&](Vec3 p) {
      p[k] = level;
      return p;
    };
    const Vec3 a = on_plane(Vec3(u(rng), u(rng), u(rng)) * 50.0f);
    const Vec3 b = on_plane(Vec3(u(rng), u(rng), u(rng)) * 50.0f);
    const Vec3 c = on_plane(Vec3(u(rng), u(rng), u(rng)) * 50.0f);
    const Vec3 o = i % 4 == 0 ? b : on_plane(Vec3(u(rng), u(rng), u(rng)) * 50.0f);
    const Vec3 d(u(rng), u(rng), u(rng));
    ASSERT_FALSE(ExactPlaneHitBeyond(o, d, a, b, c, 0.0f)) << i;
    ASSERT_FALSE(exact_t_internal::ExactExpansions(o, d, a, b, c, 0.0f)) << i;
  }
  // One ulp off the plane, toward it: beyond 0 (the shortcut does not apply).
  const Vec3 a(0, 0, 1), b(1, 0, 1), c(0, 1, 1);
  const Vec3 o(0.25f, 0.25f, std::nextafter(1.0f, 0.0f));
  EXPECT_TRUE(ExactPlaneHitBeyond(o, Vec3(0, 0, 1), a, b, c, 0.0f));
  EXPECT_FALSE(ExactPlaneHitBeyond(Vec3(0.25f, 0.25f, 1.0f), Vec3(0, 0, 1), a, b, c, 0.0f));
}

TEST(RayCheck, RejectsNanInfZeroAndFlushesDenormals) {
  const float nan = std::nanf(""), inf = INFINITY;
  Ray r{{0, 0, 0}, {1, 0, 0}};
  EXPECT_TRUE(SanitizeRay(&r));
  for (Ray bad : {Ray{{nan, 0, 0}, {1, 0, 0}}, Ray{{0, 0, 0}, {nan, 0, 0}},
                  Ray{{inf, 0, 0}, {1, 0, 0}}, Ray{{0, 0, 0}, {1, inf, 0}},
                  Ray{{0, 0, 0}, {0, 0, 0}}, Ray{{0, 0, 0}, {1, 0, 0}, nan, 1},
                  Ray{{0, 0, 0}, {1, 0, 0}, 0, nan}, Ray{{0, 0, 0}, {1, 0, 0}, 2, 1},
                  Ray{{0, 0, 0}, {1e-40f, -1e-41f, 0}}}) {
    EXPECT_FALSE(SanitizeRay(&bad));
  }
  Ray denormal{{0, 0, 0}, {1, 1e-40f, -1e-40f}};
  ASSERT_TRUE(SanitizeRay(&denormal));
  EXPECT_EQ(denormal.dir.y, 0.0f);
  EXPECT_FALSE(std::signbit(denormal.dir.y));
  EXPECT_EQ(denormal.dir.z, 0.0f);
  EXPECT_TRUE(std::signbit(denormal.dir.z));
}

}  // namespace
}  // namespace kdtree
