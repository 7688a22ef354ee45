#include "cc/render/secondary_rays.h"

#include <cmath>
#include <random>

#include "cc/kdtree/brute_force.h"
#include "gtest/gtest.h"

namespace kdtree {
namespace {

// A tilted, finely triangulated square (n x n quads), scaled and moved.
TriangleSoup TiltedGrid(int n, float scale, const Vec3& offset) {
  TriangleSoup soup;
  auto p = [&](int i, int j) {
    const float x = static_cast<float>(i) / n - 0.5f, z = static_cast<float>(j) / n - 0.5f;
    return Vec3(x, 0.3f * x + 0.1f * z, z) * scale + offset;
  };
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      soup.Add(p(i, j), p(i + 1, j), p(i + 1, j + 1));
      soup.Add(p(i, j), p(i + 1, j + 1), p(i, j + 1));
    }
  }
  return soup;
}

// No self-intersection at any scale or distance from the origin: every shadow
// ray from a lit flat surface to a light above it misses, and every ray to a
// light below it is blocked by the surface itself.
TEST(SecondaryRays, NoSelfShadowingAtAnyScale) {
  for (const float scale : {1e-4f, 1.0f, 1e4f}) {
    for (const float shift : {0.0f, 100.0f}) {
      const Vec3 offset = Vec3(shift, -shift, 0.5f * shift) * scale;
      const TriangleSoup soup = TiltedGrid(16, scale, offset);
      const BruteForce bf(soup);
      std::mt19937 rng(7);
      std::uniform_real_distribution<float> uni(-0.45f, 0.45f);
      int hits = 0;
      for (int k = 0; k < 500; ++k) {
        const Vec3 target = Vec3(uni(rng), 0, uni(rng)) * scale + offset;
        Ray ray;
        ray.origin = Vec3(0.2f, 2.0f, 1.0f) * scale + offset;
        ray.dir = Normalize(target - ray.origin);
        const Hit hit = bf.Intersect(ray);
        if (!hit.hit()) continue;
        ++hits;
        const SurfacePoint sp = MakeSurfacePoint(soup, ray, hit);
        EXPECT_LT(Dot(sp.normal, ray.dir), 0.0f);
        const Ray up = ShadowRay(sp, Vec3(-0.3f, 3.0f, 0.2f) * scale + offset);
        EXPECT_FALSE(bf.Occluded(up)) << "scale " << scale << " shift " << shift << " ray " << k;
        const Ray down = ShadowRay(sp, Vec3(0.1f, -3.0f, 0.0f) * scale + offset);
        EXPECT_TRUE(bf.Occluded(down)) << "scale " << scale << " shift " << shift << " ray " << k;
      }
      EXPECT_GT(hits, 400);
    }
  }
}

TEST(SecondaryRays, ShadowRayStopsShortOfTheLight) {
  SurfacePoint sp;
  sp.p = Vec3(0, 0, 0);
  sp.normal = Vec3(0, 1, 0);
  sp.eps = 1e-5f;
  sp.origin = Vec3(0, 1e-5f, 0);
  const Ray r = ShadowRay(sp, Vec3(0, 10, 0));
  EXPECT_NEAR(Length(r.dir), 1.0f, 1e-6f);
  EXPECT_LT(r.tmax, 10.0f - 1e-5f);
  EXPECT_GT(r.tmax, 10.0f - 1e-3f);
  EXPECT_EQ(r.tmin, 0.0f);
}

TEST(SecondaryRays, AoRaysAreCosineDistributedInTheHemisphere) {
  SurfacePoint sp;
  sp.p = Vec3(1, 2, 3);
  sp.normal = Normalize(Vec3(0.3f, -0.8f, 0.5f));
  sp.eps = 1e-4f;
  sp.origin = sp.p + sp.normal * sp.eps;
  double mean_cos = 0;
  const int n = 20000;
  for (int s = 0; s < n; ++s) {
    const Ray r = AoRay(sp, 12345, s, 0.5f);
    const float c = Dot(r.dir, sp.normal);
    EXPECT_GE(c, 0.0f);
    EXPECT_NEAR(Length(r.dir), 1.0f, 1e-5f);
    EXPECT_EQ(r.tmax, 0.5f);
    mean_cos += c;
  }
  // E[cos] = 2/3 for the cosine-weighted hemisphere.
  EXPECT_NEAR(mean_cos / n, 2.0 / 3.0, 0.01);
  // Deterministic.
  EXPECT_EQ(AoRay(sp, 7, 3, 1.0f).dir, AoRay(sp, 7, 3, 1.0f).dir);
}

}  // namespace
}  // namespace kdtree
