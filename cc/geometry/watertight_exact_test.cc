// The watertight test against exact arithmetic (watertight.h): its float edge
// functions are trusted only beyond EdgeErrorBound, and then their signs are
// the exact ones; with the exact fallback it reports a hit exactly when the
// ray's line meets the closed triangle beyond the origin.
#include <cmath>
#include <random>

#include "cc/geometry/exact_t.h"
#include "cc/geometry/exact_triple.h"
#include "cc/geometry/watertight.h"
#include "gtest/gtest.h"

namespace kdtree {
namespace {

// Exact sign of edge function i of triangle (a, b, c) for `ray`, oriented like
// Shear's e[i]: U ~ d . (C x B), V ~ d . (A x C), W ~ d . (B x A).
int ExactEdgeSign(const Ray& ray, const Vec3 v[3], int i) {
  return TripleSign(ray.dir, v[(i + 2) % 3], ray.origin, v[(i + 1) % 3], ray.origin);
}

// Exactly: the ray's line meets the closed triangle at t > 0.
bool ExactHit(const Ray& ray, const Vec3 v[3]) {
  int s[3];
  for (int i = 0; i < 3; ++i) s[i] = ExactEdgeSign(ray, v, i);
  const bool neg = s[0] < 0 || s[1] < 0 || s[2] < 0, pos = s[0] > 0 || s[1] > 0 || s[2] > 0;
  if (neg == pos) return false;
  return ExactPlaneHitBeyond(ray.origin, ray.dir, v[0], v[1], v[2], 0.0f);
}

// A ray from a random origin aimed at a point on (or a few ulps off) an edge
// of a random triangle, at a random scale and distance from the world origin.
struct Case {
  Ray ray;
  Vec3 v[3];
};
Case GrazingCase(std::mt19937* rng, float scale, float offset) {
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f), frac(0.0f, 1.0f);
  std::uniform_int_distribution<int> nudge(-3, 3), edge(0, 2);
  auto point = [&](float s) {
    return Vec3(offset + s * unit(*rng), offset + s * unit(*rng), offset + s * unit(*rng));
  };
  Case c;
  for (Vec3& p : c.v) p = point(scale);
  const int i = edge(*rng);
  const Vec3 &p = c.v[i], &q = c.v[(i + 1) % 3];
  Vec3 target = p + (q - p) * frac(*rng);
  for (int k = 0; k < 3; ++k) {
    for (int n = nudge(*rng); n != 0; n += n > 0 ? -1 : 1) {
      target[k] = std::nextafter(target[k], n > 0 ? INFINITY : -INFINITY);
    }
  }
  c.ray.origin = point(20 * scale);
  c.ray.dir = target - c.ray.origin;
  c.ray.tmin = 0;
  c.ray.tmax = INFINITY;
  return c;
}

struct Scale {
  float scale, offset;
};
constexpr Scale kScales[] = {{1, 0},      {1, 1e3f},     {1e-3f, 1e5f}, {50, 1.5e5f},
                             {1e-30f, 0}, {1e25f, 0},    {1e-20f, 1e-18f}};

TEST(WatertightExact, TrustedFloatSignsAreTheExactSigns) {
  std::mt19937 rng(7);
  int trusted = 0, untrusted = 0, float_wrong = 0;
  for (const Scale& sc : kScales) {
    for (int k = 0; k < 20000; ++k) {
      const Case c = GrazingCase(&rng, sc.scale, sc.offset);
      const WatertightRay w = MakeWatertightRay(c.ray);
      const watertight_internal::Sheared s = watertight_internal::Shear(w, c.v[0], c.v[1], c.v[2]);
      const float bound = watertight_internal::EdgeErrorBound(w, s);
      for (int i = 0; i < 3; ++i) {
        const int exact = ExactEdgeSign(c.ray, c.v, i);
        const int fsign = s.e[i] > 0 ? 1 : (s.e[i] < 0 ? -1 : 0);
        float_wrong += fsign != exact;
        if (std::fabs(s.e[i]) > bound) {
          ++trusted;
          ASSERT_EQ(fsign, exact) << "scale " << sc.scale << " offset " << sc.offset << " case "
                                  << k << " edge " << i << " e " << s.e[i] << " bound " << bound;
        } else {
          ++untrusted;
        }
      }
    }
  }
  // Rounding really does flip signs on these rays. Every edge of the scales
  // whose products leave float's range (1e-30, 1e-20, 1e25) is untrusted and
  // decided exactly; elsewhere the edge aimed at mostly is.
  EXPECT_GT(float_wrong, 10000);
  EXPECT_GT(trusted, 100000);
  EXPECT_GT(untrusted, 100000);
}

TEST(WatertightExact, HitsExactlyWhenExactArithmeticSaysSo) {
  std::mt19937 rng(11);
  int hits = 0, misses = 0;
  for (const Scale& sc : kScales) {
    for (int k = 0; k < 20000; ++k) {
      const Case c = GrazingCase(&rng, sc.scale, sc.offset);
      float t, u, v;
      const bool hit = IntersectTriangleWatertight(MakeWatertightRay(c.ray), c.v[0], c.v[1],
                                                   c.v[2], 0.0f, INFINITY, &t, &u, &v);
      ASSERT_EQ(hit, ExactHit(c.ray, c.v))
          << "scale " << sc.scale << " offset " << sc.offset << " case " << k;
      (hit ? hits : misses)++;
    }
  }
  EXPECT_GT(hits, 1000);
  EXPECT_GT(misses, 1000);
}

TEST(WatertightExact, RandomRaysRarelyNeedTheFallback) {
  // Rays aimed anywhere near the triangle: the bound is tight enough that the
  // exact fallback stays rare (its cost is measured in the renderer's runs).
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  int undecided = 0, n = 0;
  for (int k = 0; k < 100000; ++k) {
    const Vec3 v[3] = {{unit(rng), unit(rng), 10}, {unit(rng), unit(rng), 10},
                       {unit(rng), unit(rng), 10}};
    const Ray ray{{0, 0, 0}, Vec3(2 * unit(rng), 2 * unit(rng), 10)};
    const WatertightRay w = MakeWatertightRay(ray);
    const watertight_internal::Sheared s = watertight_internal::Shear(w, v[0], v[1], v[2]);
    undecided += !watertight_internal::SignsDecided(s.e, watertight_internal::EdgeErrorBound(w, s));
    ++n;
  }
  EXPECT_LT(undecided, n / 1000);
}

}  // namespace
}  // namespace kdtree
