#include "cc/embree/embree_tracer.h"

#include <cmath>
#include <cstdio>
#include <vector>

#include "cc/kdtree/brute_force.h"
#include "cc/kdtree/test_scenes.h"
#include "cc/render/compare.h"
#include "cc/render/exact_check.h"
#include "cc/render/kdtree_tracer.h"
#include "cc/render/renderer.h"
#include "cc/render/test_scene.h"
#include "gtest/gtest.h"

namespace kdtree {
namespace {

TEST(EmbreeTracer, AgreesWithBruteForceOnRenderedRaysExceptGrazing) {
  for (const EmbreeQuality q : {EmbreeQuality::kLow, EmbreeQuality::kMedium, EmbreeQuality::kHigh}) {
    for (const float scale : {1e-3f, 1.0f, 1e3f}) {
      const TriangleSoup soup = testing::SphereOnGround(scale);
      const BruteForce bf(soup);
      const BruteForceTracer brute(bf);
      EmbreeOptions opt;
      opt.quality = q;
      absl::StatusOr<std::unique_ptr<EmbreeTracer>> embree = EmbreeTracer::Create(soup, opt);
      ASSERT_TRUE(embree.ok()) << embree.status();
      EXPECT_GE((*embree)->build_seconds(), 0.0);
      View view = testing::SphereView(64, 64, scale);
      view.ao.samples = 2;
      view.ao.distance = 0.4f * scale;
      RenderOptions ro;
      ro.record_rays = true;
      const RenderResult ref = Render(soup, brute, view, ro);
      ASSERT_GT(ref.shadow.rays, 0u);
      const Disagreements d = CompareTracers(ref.rays, soup, brute, **embree);
      EXPECT_EQ(d.all.other(), 0u) << EmbreeQualityName(q) << " scale " << scale << ": "
                                   << d.ToJson() << (d.examples.empty() ? "" : d.examples[0]);
      EXPECT_LE(d.all.total(), ref.rays.size() / 1000);
      // Embree's own render sees (nearly) the same picture.
      const RenderResult own = Render(soup, **embree, view, RenderOptions());
      EXPECT_NEAR(static_cast<double>(own.p_hit), static_cast<double>(ref.p_hit), 3.0);
      EXPECT_NEAR(static_cast<double>(own.s_hit), static_cast<double>(ref.s_hit), 3.0);
    }
  }
}

// Random rays against brute force: the same hits, but for rays passing a
// triangle edge within kGrazingUlps (a few at most).
void CheckRandomRays(const EmbreeOptions& options) {
  const TriangleSoup soup = testing::BumpySphere(3, 9);
  const BruteForce bf(soup);
  absl::StatusOr<std::unique_ptr<EmbreeTracer>> embree = EmbreeTracer::Create(soup, options);
  ASSERT_TRUE(embree.ok()) << embree.status();
  int hits = 0, grazing_only = 0;
  for (const Ray& ray : testing::RandomRays(soup, 20000, 3)) {
    const Hit a = bf.Intersect(ray);
    const Hit b = (*embree)->Intersect(ray);
    hits += a.hit();
    const bool same = a.hit() == b.hit() && (!a.hit() || std::fabs(a.t - b.t) <= 1e-4f * std::fmax(a.t, b.t));
    if (same) {
      if (a.hit()) {
        EXPECT_EQ(a.tri, b.tri);
      }
      EXPECT_EQ(bf.Occluded(ray), (*embree)->Occluded(ray));
      continue;
    }
    // Either tracer's triangle is passed within 4 ulps of an edge (compare.h).
    bool grazing = false;
    for (const Hit& h : {a, b}) {
      if (!h.hit()) continue;
      const ExactTriangleHit e = ExactIntersect(ray, soup.a(h.tri), soup.b(h.tri), soup.c(h.tri));
      grazing |= e.edge_distance <= kGrazingUlps * FloatUlp(e.magnitude);
    }
    EXPECT_TRUE(grazing) << "t " << a.t << " vs " << b.t;
    ++grazing_only;
  }
  EXPECT_GT(hits, 5000);
  EXPECT_LT(grazing_only, 10);
}

// Default flags and RTC_SCENE_FLAG_ROBUST alike.
TEST(EmbreeTracer, AgreesWithBruteForceOnRandomRays) {
  for (const bool robust : {false, true}) {
    SCOPED_TRACE(robust ? "robust" : "default flags");
    EmbreeOptions options;
    options.robust = robust;
    CheckRandomRays(options);
  }
}

// Embree's packet queries against its single-ray ones, on packets of 4x4
// camera rays and of 1 to 16 random rays. Its packet and single-ray kernels
// are separate code, so a grazing ray may differ: allowed on a few rays only.
TEST(EmbreeTracer, PacketsAgreeWithSingleRays) {
  const TriangleSoup soup = testing::BumpySphere(3, 9);
  absl::StatusOr<std::unique_ptr<EmbreeTracer>> embree = EmbreeTracer::Create(soup, EmbreeOptions());
  ASSERT_TRUE(embree.ok()) << embree.status();
  std::printf("native ray16: %d\n", (*embree)->native_ray16());
  const std::vector<Ray> cam = testing::CameraRays(soup, 64, 64);
  std::vector<Ray> rays;
  for (int y = 0; y < 64; y += 4) {
    for (int x = 0; x < 64; x += 4) {
      for (int j = 0; j < 4; ++j) {
        for (int i = 0; i < 4; ++i) rays.push_back(cam[(y + j) * 64 + x + i]);
      }
    }
  }
  const std::vector<Ray> random = testing::RandomRays(soup, 4000, 5);
  rays.insert(rays.end(), random.begin(), random.end());
  int hits = 0, differ = 0;
  for (size_t k = 0; k < rays.size(); k += 16) {
    const int n = k < cam.size() ? 16 : 1 + static_cast<int>(k / 16 % 16);
    Hit got[16];
    bool occ[16];
    (*embree)->IntersectPacket(&rays[k], n, got);
    (*embree)->OccludedPacket(&rays[k], n, nullptr, occ);
    for (int i = 0; i < n; ++i) {
      const Hit want = (*embree)->Intersect(rays[k + i]);
      hits += want.hit();
      differ += !(got[i].tri == want.tri && got[i].t == want.t) ||
                occ[i] != (*embree)->Occluded(rays[k + i]);
    }
  }
  EXPECT_GT(hits, 2000);
  EXPECT_LE(differ, 5);
}

// The BVH's bytes: some per triangle (a leaf holds its triangles' vertices),
// far fewer than a kilobyte, and more for more triangles.
TEST(EmbreeTracer, CountsItsBvhBytes) {
  int64_t last = 0;
  for (const int levels : {3, 5}) {
    const TriangleSoup soup = testing::BumpySphere(levels, 7);
    absl::StatusOr<std::unique_ptr<EmbreeTracer>> embree =
        EmbreeTracer::Create(soup, EmbreeOptions());
    ASSERT_TRUE(embree.ok()) << embree.status();
    const int64_t bytes = (*embree)->bvh_bytes();
    const int64_t n = static_cast<int64_t>(soup.size());
    EXPECT_GE(bytes, 16 * n) << soup.size() << " triangles";
    EXPECT_LE(bytes, 1024 * n) << soup.size() << " triangles";
    EXPECT_GT(bytes, last);
    last = bytes;
  }
}

TEST(EmbreeTracer, QualityNames) {
  EXPECT_EQ(*ParseEmbreeQuality("HIGH"), EmbreeQuality::kHigh);
  EXPECT_EQ(*ParseEmbreeQuality("low"), EmbreeQuality::kLow);
  EXPECT_FALSE(ParseEmbreeQuality("ultra").ok());
  EXPECT_STREQ(EmbreeQualityName(EmbreeQuality::kMedium), "medium");
}

TEST(EmbreeTracer, EmptySoupIsAnError) {
  EXPECT_FALSE(EmbreeTracer::Create(TriangleSoup(), EmbreeOptions()).ok());
}

}  // namespace
}  // namespace kdtree
