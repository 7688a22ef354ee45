#include "cc/render/renderer.h"

#include <algorithm>
#include <string>
#include <vector>

#include "cc/kdtree/brute_force.h"
#include "cc/kdtree/builder.h"
#include "cc/render/compare.h"
#include "cc/render/kdtree_tracer.h"
#include "cc/render/test_scene.h"
#include "cc/render/traversal_counts.h"
#include "gtest/gtest.h"

namespace kdtree {
namespace {

struct Fixture {
  TriangleSoup soup = testing::SphereOnGround();
  KdTree tree;
  Fixture() {
    absl::StatusOr<Config> config = Preset("clipping-pruning");
    absl::StatusOr<KdTree> t = BuildKdTree(soup, *config);
    EXPECT_TRUE(t.ok());
    tree = *std::move(t);
  }
};

const Fixture& Scene() {
  static const Fixture* f = new Fixture();
  return *f;
}

RenderResult RenderKd(const View& view, int threads, bool record) {
  const KdTreeTracer tracer(Scene().tree);
  RenderOptions opt;
  opt.threads = threads;
  opt.record_rays = record;
  return Render(Scene().soup, tracer, view, opt);
}

TEST(RenderBytes, CountsWhatRenderAllocatesAtWorst) {
  View view;  // 800 x 800
  view.lights.resize(2);
  RenderOptions options;
  const uint64_t pixels = 800 * 800;
  EXPECT_EQ(RenderBytes(view, options), pixels * (sizeof(Hit) + 3 + 2));
  options.record_rays = true;  // a primary and two shadow rays per pixel
  EXPECT_EQ(RenderBytes(view, options), pixels * (sizeof(Hit) + 3 + 2 + 3 * 3 * sizeof(RayRecord)));
  options.cast_shadow_rays = false;
  EXPECT_EQ(RenderBytes(view, options), pixels * (sizeof(Hit) + 3 + 3 * sizeof(RayRecord)));
}

TEST(Renderer, NoLightTracesNoShadowRays) {
  const RenderResult r = RenderKd(testing::SphereView(64, 48, 1.0f, /*with_light=*/false), 1, true);
  EXPECT_EQ(r.primary.rays, 64u * 48u);
  EXPECT_EQ(r.p_hit + r.p_miss, 64u * 48u);
  EXPECT_GT(r.p_hit, 0u);
  EXPECT_GT(r.p_miss, 0u);
  EXPECT_EQ(r.shadow.rays, 0u);
  EXPECT_EQ(r.s_hit + r.s_miss, 0u);
  EXPECT_EQ(r.ao.rays, 0u);
  EXPECT_EQ(r.rays.size(), 64u * 48u);
  EXPECT_EQ(r.rgb.size(), 64u * 48u * 3u);
}

TEST(Renderer, OneShadowRayPerPrimaryHit) {
  const RenderResult r = RenderKd(testing::SphereView(64, 64), 1, true);
  EXPECT_EQ(r.s_hit + r.s_miss, r.p_hit);
  EXPECT_EQ(r.shadow.rays, r.p_hit);
  EXPECT_GT(r.s_hit, 0u);   // the sphere shadows the ground
  EXPECT_GT(r.s_miss, 0u);  // and the lit parts are lit
  EXPECT_EQ(r.rays.size(), r.p_hit + r.p_miss + r.s_hit + r.s_miss);
  EXPECT_EQ(r.total_rays(), r.rays.size());
}

TEST(Renderer, ShadowsOffTracesNoShadowRays) {
  const KdTreeTracer tracer(Scene().tree);
  RenderOptions opt;
  opt.cast_shadow_rays = false;
  const RenderResult r = Render(Scene().soup, tracer, testing::SphereView(32, 32), opt);
  EXPECT_EQ(r.shadow.rays, 0u);
  EXPECT_GT(r.p_hit, 0u);
}

TEST(Renderer, AmbientOcclusionOnlyWhenAsked) {
  View view = testing::SphereView(32, 32);
  view.ao.samples = 4;
  view.ao.distance = 0.5f;
  const RenderResult r = RenderKd(view, 1, true);
  EXPECT_EQ(r.ao.rays, 4 * r.p_hit);
  EXPECT_EQ(r.ao_hit + r.ao_miss, r.ao.rays);
  EXPECT_GT(r.ao_hit, 0u);  // the ground under the sphere is occluded
  EXPECT_EQ(r.rays.size(), r.p_hit + r.p_miss + r.shadow.rays + r.ao.rays);
}

TEST(Renderer, IdenticalForOneAndTwoThreads) {
  View view = testing::SphereView(96, 80);
  view.ao.samples = 2;
  view.ao.distance = 0.3f;
  const RenderResult a = RenderKd(view, 1, true);
  const RenderResult b = RenderKd(view, 2, true);
  EXPECT_EQ(a.rgb, b.rgb);
  EXPECT_EQ(a.p_hit, b.p_hit);
  EXPECT_EQ(a.s_hit, b.s_hit);
  EXPECT_EQ(a.ao_hit, b.ao_hit);
  EXPECT_TRUE(a.rays == b.rays);
}

TEST(Renderer, TilesGiveTheSameImageAsOneThread) {
  View view = testing::SphereView(100, 70);  // not a multiple of the tile sizes
  view.ao.samples = 2;
  view.ao.distance = 0.3f;
  const KdTreeTracer tracer(Scene().tree);
  const RenderResult a = RenderKd(view, 1, false);
  for (int tile : {0, 7, 16, 64}) {
    RenderOptions opt;
    opt.threads = 2;
    opt.tile_size = tile;
    const RenderResult b = Render(Scene().soup, tracer, view, opt);
    EXPECT_EQ(a.rgb, b.rgb) << "tile " << tile;
    EXPECT_EQ(a.p_hit, b.p_hit) << "tile " << tile;
    EXPECT_EQ(a.s_hit, b.s_hit) << "tile " << tile;
    EXPECT_EQ(a.ao_hit, b.ao_hit) << "tile " << tile;
    EXPECT_EQ(a.total_rays(), b.total_rays()) << "tile " << tile;
    for (size_t p = 0; p < a.primary_hits.size(); ++p) {
      ASSERT_EQ(a.primary_hits[p].tri, b.primary_hits[p].tri) << "pixel " << p;
      ASSERT_EQ(a.primary_hits[p].t, b.primary_hits[p].t) << "pixel " << p;
    }
  }
  EXPECT_GT(a.p_hit, 0u);
  EXPECT_GT(a.s_hit, 0u);
}

// Packets of 4x4 pixels (odd image sides and tiles: blocks of 1 to 16 rays)
// give the single-ray hits, occlusions and image, with the kd-tree's packet
// traversal and with the Tracer default (brute force, one ray at a time),
// also with shadow rays leaving their origin triangle untested
// (Tracer::OccludedPacket with origin triangles).
TEST(Renderer, PacketsGiveTheSingleRayImage) {
  View view = testing::SphereView(101, 71);
  view.ao.samples = 2;
  view.ao.distance = 0.3f;
  const KdTreeTracer kd(Scene().tree);
  const BruteForce bf(Scene().soup);
  const BruteForceTracer brute(bf);
  const RenderResult a = RenderKd(view, 1, false);
  for (int threads : {1, 2}) {
    for (int tile : {0, 7, 16}) {
      for (const Tracer* tracer : {static_cast<const Tracer*>(&kd), static_cast<const Tracer*>(&brute)}) {
        for (bool skip_origin : {false, true}) {
          RenderOptions opt;
          opt.threads = threads;
          opt.tile_size = tile;
          opt.packets = true;
          opt.skip_origin = skip_origin;
          const RenderResult b = Render(Scene().soup, *tracer, view, opt);
          const std::string what = tracer->name() + " threads " + std::to_string(threads) +
                                   " tile " + std::to_string(tile) + " skip_origin " +
                                   std::to_string(skip_origin);
          EXPECT_EQ(a.rgb, b.rgb) << what;
          EXPECT_EQ(a.p_hit, b.p_hit) << what;
          EXPECT_EQ(a.s_hit, b.s_hit) << what;
          EXPECT_EQ(a.ao_hit, b.ao_hit) << what;
          EXPECT_EQ(a.total_rays(), b.total_rays()) << what;
          for (size_t p = 0; p < a.primary_hits.size(); ++p) {
            ASSERT_EQ(a.primary_hits[p].tri, b.primary_hits[p].tri) << what << " pixel " << p;
            ASSERT_EQ(a.primary_hits[p].t, b.primary_hits[p].t) << what << " pixel " << p;
          }
        }
        if (threads == 2) break;  // brute force at 2 threads adds nothing
      }
    }
  }
  EXPECT_GT(a.s_hit, 0u);
}

// Logs each query's ray in call order; the packet queries are Tracer's
// defaults, one ray at a time, so they log the packets' rays in order.
class LoggingTracer : public Tracer {
 public:
  explicit LoggingTracer(const Tracer& inner) : inner_(inner) {}
  std::string name() const override { return "logging"; }
  using Tracer::Occluded;
  Hit Intersect(const Ray& ray) const override {
    log_.push_back(ray);
    return inner_.Intersect(ray);
  }
  bool Occluded(const Ray& ray, uint32_t origin_tri) const override {
    log_.push_back(ray);
    return inner_.Occluded(ray, origin_tri);
  }
  const std::vector<Ray>& log() const { return log_; }

 private:
  const Tracer& inner_;
  mutable std::vector<Ray> log_;
};

// Single rays and packets visit the pixels in the same order (renderer.h,
// "Pixel order"), so the two modes differ in how they trace only.
TEST(Renderer, SingleRaysComeInThePacketsOrder) {
  const View view = testing::SphereView(37, 22);  // blocks cut at both edges
  const KdTreeTracer kd(Scene().tree);
  const LoggingTracer single(kd), packets(kd);
  RenderOptions opt;
  Render(Scene().soup, single, view, opt);
  opt.packets = true;
  Render(Scene().soup, packets, view, opt);
  ASSERT_EQ(single.log().size(), packets.log().size());
  ASSERT_GT(single.log().size(), 37u * 22u);  // shadow rays too
  for (size_t i = 0; i < single.log().size(); ++i) {
    const Ray& a = single.log()[i];
    const Ray& b = packets.log()[i];
    ASSERT_TRUE(a.origin.x == b.origin.x && a.origin.y == b.origin.y &&
                a.origin.z == b.origin.z && a.dir.x == b.dir.x && a.dir.y == b.dir.y &&
                a.dir.z == b.dir.z && a.tmax == b.tmax)
        << "query " << i;
  }
}

// Shadow and AO rays that leave their origin triangle untested
// (RenderOptions::skip_origin) give every recorded result, hence the image.
TEST(Renderer, SkippingTheOriginTriangleChangesNoResult) {
  View view = testing::SphereView(90, 70);
  view.ao.samples = 3;
  view.ao.distance = 0.3f;
  const KdTreeTracer kd(Scene().tree);
  const BruteForce bf(Scene().soup);
  const RenderResult a = RenderKd(view, 1, true);
  for (int threads : {1, 2}) {
    RenderOptions opt;
    opt.threads = threads;
    opt.skip_origin = true;
    opt.record_rays = threads == 1;
    const RenderResult b = Render(Scene().soup, kd, view, opt);
    EXPECT_EQ(a.rgb, b.rgb) << threads;
    EXPECT_EQ(a.s_hit, b.s_hit) << threads;
    EXPECT_EQ(a.ao_hit, b.ao_hit) << threads;
    if (threads == 1) {
      ASSERT_EQ(a.rays.size(), b.rays.size());
      for (size_t i = 0; i < a.rays.size(); ++i) ASSERT_EQ(a.rays[i].hit, b.rays[i].hit) << i;
    }
  }
  size_t secondary = 0;
  for (const RayRecord& rec : a.rays) {
    if (rec.kind == RayKind::kPrimary) continue;
    ++secondary;
    const uint32_t origin = a.primary_hits[rec.pixel].tri;
    ASSERT_EQ(kd.Occluded(rec.ray(), origin), bf.Occluded(rec.ray())) << rec.pixel;
  }
  EXPECT_GT(secondary, 1000u);
  EXPECT_GT(a.s_hit, 0u);
  EXPECT_GT(a.ao_hit, 0u);
}

TEST(Renderer, KdTreeAndBruteForceGiveIdenticalHitBuffers) {
  const View view = testing::SphereView(80, 80);
  const BruteForce bf(Scene().soup);
  const BruteForceTracer brute(bf);
  RenderOptions opt;
  opt.record_rays = true;
  const RenderResult ref = Render(Scene().soup, brute, view, opt);
  const RenderResult kd = RenderKd(view, 1, true);
  ASSERT_EQ(ref.primary_hits.size(), kd.primary_hits.size());
  for (size_t i = 0; i < ref.primary_hits.size(); ++i) {
    EXPECT_EQ(ref.primary_hits[i].tri, kd.primary_hits[i].tri) << "pixel " << i;
    EXPECT_EQ(ref.primary_hits[i].t, kd.primary_hits[i].t) << "pixel " << i;
  }
  EXPECT_TRUE(ref.rays == kd.rays);
  EXPECT_EQ(ref.rgb, kd.rgb);
  const Disagreements d = CompareTracers(kd.rays, Scene().soup, KdTreeTracer(Scene().tree), brute);
  EXPECT_EQ(d.all.total(), 0u) << d.ToJson();
}

TEST(Renderer, CountingPassReplaysTheSameResults) {
  const RenderResult r = RenderKd(testing::SphereView(64, 64), 1, true);
  const RayCounts c = CountTraversal(Scene().tree, r.rays);
  EXPECT_EQ(c.result_mismatches, 0u);
  EXPECT_EQ(c.all.rays, r.rays.size());
  EXPECT_EQ(c.by_kind[0].rays, r.primary.rays);
  EXPECT_EQ(c.by_kind[1].rays, r.shadow.rays);
  EXPECT_GT(c.n_it(), 0.0);
  EXPECT_GT(c.n_tr(), 0.0);
}

TEST(Renderer, LitImageHasShadowAndBackground) {
  const RenderResult r = RenderKd(testing::SphereView(64, 64), 1, false);
  // Top-left corner misses everything: background.
  EXPECT_EQ(r.rgb[0], r.rgb[3]);
  EXPECT_FALSE(r.primary_hits[0].hit());
  // Some hit pixel is darker than another (shadow / shading variation).
  int lo = 255, hi = 0;
  for (size_t p = 0; p < r.primary_hits.size(); ++p) {
    if (!r.primary_hits[p].hit()) continue;
    lo = std::min<int>(lo, r.rgb[3 * p]);
    hi = std::max<int>(hi, r.rgb[3 * p]);
  }
  EXPECT_GT(hi - lo, 80);
}

}  // namespace
}  // namespace kdtree
