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

// No self-intersection at any scale or distance from the origin: a lit flat
// surface never shadows itself, whichever side the light is on (the origin
// goes to the light's side; spawn.h).
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
        EXPECT_FALSE(bf.Occluded(down)) << "scale " << scale << " shift " << shift << " ray " << k;
        EXPECT_FALSE(bf.Occluded(AoRay(sp, k, 0, 10.0f * scale))) << "ray " << k;
      }
      EXPECT_GT(hits, 400);
    }
  }
}

// The offset is a bound on rounding, not a fixed fraction of the coordinates:
// an occluder 2.9e-4 x scale above a surface 100 x scale away from the origin
// still blocks every shadow ray. (The former fixed offset, 1e-5 times the
// largest vertex coordinate, about 1e-3 x scale here, would start the rays above
// it, so none would be blocked.)
TEST(SecondaryRays, CloseOccluderFarFromTheOriginStillBlocks) {
  for (const float scale : {1e-4f, 1.0f, 1e4f}) {
    const Vec3 offset = Vec3(100, -100, 50) * scale;
    const TriangleSoup surface = TiltedGrid(16, scale, offset);
    TriangleSoup both = surface;  // the surface's triangles keep their indices
    const TriangleSoup lid = TiltedGrid(4, scale, offset + Vec3(0, 3e-4f, 0) * scale);
    for (size_t i = 0; i < lid.size(); ++i) both.Add(lid.a(i), lid.b(i), lid.c(i));
    const BruteForce on_surface(surface), on_both(both);
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> uni(-0.4f, 0.4f);
    int blocked = 0, hits = 0;
    for (int k = 0; k < 300; ++k) {
      Ray ray;
      ray.origin = Vec3(0.2f, 2.0f, 1.0f) * scale + offset;
      ray.dir = Normalize(Vec3(uni(rng), 0, uni(rng)) * scale + offset - ray.origin);
      const Hit hit = on_surface.Intersect(ray);
      if (!hit.hit()) continue;
      ++hits;
      const SurfacePoint sp = MakeSurfacePoint(surface, ray, hit);
      blocked += on_both.Occluded(ShadowRay(sp, Vec3(-0.1f, 3.0f, 0.2f) * scale + offset));
    }
    EXPECT_GT(hits, 250);
    EXPECT_EQ(blocked, hits) << "scale " << scale;
  }
}

TEST(SecondaryRays, ShadowRayEndsAtTheLight) {
  const TriangleSoup soup = TiltedGrid(2, 1.0f, Vec3(0, 0, 0));
  Ray primary;
  primary.origin = Vec3(0.1f, 5.0f, 0.05f);
  primary.dir = Vec3(0, -1, 0);
  const Hit hit = BruteForce(soup).Intersect(primary);
  ASSERT_TRUE(hit.hit());
  const SurfacePoint sp = MakeSurfacePoint(soup, primary, hit);
  const Vec3 light(0.5f, 10.0f, -0.5f);
  const Ray r = ShadowRay(sp, light);
  EXPECT_EQ(r.tmin, 0.0f);
  EXPECT_EQ(r.tmax, 1.0f);
  const Vec3 end = r.origin + r.dir * r.tmax;
  EXPECT_NEAR(Length(end - light), 0.0f, 1e-5f);
  // The origin is within a few ulps of the hit point, on the light's side.
  EXPECT_LT(Length(r.origin - sp.p()), 1e-6f);
  EXPECT_GT(Dot(r.origin - sp.p(), sp.normal), 0.0f);
}

TEST(SecondaryRays, AoRaysAreCosineDistributedInTheHemisphere) {
  SurfacePoint sp;
  sp.point.p = Vec3(1, 2, 3);
  sp.point.error = Vec3(1e-6f, 1e-6f, 1e-6f);
  sp.normal = Normalize(Vec3(0.3f, -0.8f, 0.5f));
  double mean_cos = 0;
  const int n = 20000;
  for (int s = 0; s < n; ++s) {
    const Ray r = AoRay(sp, 12345, s, 0.5f);
    const float c = Dot(r.dir, sp.normal);
    EXPECT_GE(c, 0.0f);
    EXPECT_NEAR(Length(r.dir), 1.0f, 1e-5f);
    EXPECT_EQ(r.tmax, 0.5f);
    EXPECT_GT(Dot(r.origin - sp.p(), sp.normal), 0.0f);  // offset to the hemisphere's side
    EXPECT_LT(Length(r.origin - sp.p()), 1e-5f);
    mean_cos += c;
  }
  // E[cos] = 2/3 for the cosine-weighted hemisphere.
  EXPECT_NEAR(mean_cos / n, 2.0 / 3.0, 0.01);
  // Deterministic.
  EXPECT_EQ(AoRay(sp, 7, 3, 1.0f).dir, AoRay(sp, 7, 3, 1.0f).dir);
}

}  // namespace
}  // namespace kdtree
