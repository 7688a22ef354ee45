// The BVH over the kd-tree's leaves (leaf_bvh.h) against the kd-tree's own
// traversal, bit for bit, and against brute force: closest hits, any hits,
// and shadow rays that leave their origin triangle untested, for every
// preset on the generated scenes, with seeded random rays, a camera, and
// axis-parallel rays that start on the planes of the boxes' faces.
#include "cc/kdtree/leaf_bvh.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "absl/strings/str_cat.h"
#include "cc/geometry/spawn.h"
#include "cc/kdtree/brute_force.h"
#include "cc/kdtree/builder.h"
#include "cc/kdtree/leaf_layout.h"
#include "cc/kdtree/ray_packet.h"
#include "cc/kdtree/test_scenes.h"
#include "cc/kdtree/traversal.h"
#include "gtest/gtest.h"

namespace kdtree {
namespace {

TriangleSoup MakeSoup(const std::string& name) {
  if (name == "sphere") return testing::BumpySphere(4, 1);
  if (name == "voxels") return testing::VoxelGrid(10, 6, 10, 2);
  if (name == "thin") return testing::ThinSoup(2000, 3);
  if (name == "flat") return testing::FlatScene(1000, 4);
  return {};
}

// Rays along the axes (directions with +-0 components) from points on the
// voxel grid's integer planes, which are its leaves' box faces too.
std::vector<Ray> AxisRays(int count, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> cell(-1, 11), axis(0, 2), sign(0, 1);
  std::vector<Ray> rays;
  for (int i = 0; i < count; ++i) {
    Ray r;
    for (int k = 0; k < 3; ++k) {
      r.origin[k] = static_cast<float>(cell(rng)) + (sign(rng) ? 0.5f : 0.0f);
      r.dir[k] = sign(rng) ? 0.0f : -0.0f;
    }
    r.dir[axis(rng)] = sign(rng) ? 1.0f : -1.0f;
    rays.push_back(r);
  }
  return rays;
}

// The lanes of packets of 16 consecutive rays whose closest hit or any hit
// through `bvh` differs from the kd-tree's single ray, bit for bit.
int PacketMismatches(const KdTree& tree, const LeafBvh& bvh, const std::vector<Ray>& rays) {
  int bad = 0;
  for (size_t i = 0; i < rays.size(); i += kRayPacketSize) {
    const int n = static_cast<int>(std::min<size_t>(kRayPacketSize, rays.size() - i));
    Hit hits[kRayPacketSize];
    bool occluded[kRayPacketSize];
    IntersectPacketLeafBvh(tree, bvh, &rays[i], n, hits);
    OccludedPacketLeafBvh(tree, bvh, &rays[i], n, nullptr, occluded);
    for (int l = 0; l < n; ++l) {
      const Hit want = Intersect(tree, rays[i + l]);
      bad += !testing::BitwiseSameHit(hits[l], want) + (occluded[l] != want.hit());
    }
  }
  return bad;
}

class LeafBvhVsKd : public ::testing::TestWithParam<std::tuple<std::string, std::string>> {};

TEST_P(LeafBvhVsKd, SameAnswers) {
  const auto& [scene, preset] = GetParam();
  const TriangleSoup soup = MakeSoup(scene);
  absl::StatusOr<Config> config = Preset(preset);
  ASSERT_TRUE(config.ok());
  absl::StatusOr<KdTree> tree = BuildKdTree(soup, *config);
  ASSERT_TRUE(tree.ok()) << tree.status();
  const LeafBvh bvh = BuildLeafBvh(*tree);
  ASSERT_FALSE(bvh.nodes.empty());
  const BruteForce bf(soup);
  std::vector<Ray> rays = testing::RandomRays(soup, 20000, 7);
  for (const Ray& r : testing::CameraRays(soup, 120, 120)) rays.push_back(r);
  for (const Ray& r : AxisRays(3000, 9)) rays.push_back(r);
  const Vec3 light = tree->bounds.hi + tree->bounds.Extent() * 0.5f;
  TraversalOptions from_end;
  from_end.from_end = true;
  int closest = 0, any = 0, shadow = 0, hits = 0, shadows = 0;
  std::vector<Ray> shadow_rays;
  std::vector<uint32_t> shadow_origins;
  std::vector<char> shadow_blocked;
  for (size_t i = 0; i < rays.size(); ++i) {
    const Hit want = Intersect(*tree, rays[i]);
    const Hit got = IntersectLeafBvh(*tree, bvh, rays[i]);
    closest += !testing::BitwiseSameHit(got, want);
    any += OccludedLeafBvh(*tree, bvh, rays[i]) != want.hit();
    if (i % 16 == 0) closest += !testing::BitwiseSameHit(got, bf.Intersect(rays[i]));
    if (!want.hit()) continue;
    ++hits;
    // A shadow ray from the hit to a light beyond the box, as the renderer
    // spawns it, leaving its origin triangle untested.
    const Vec3 &a = soup.a(want.tri), &b = soup.b(want.tri), &c = soup.c(want.tri);
    const Ray s = SpawnShadowRay(HitPointWithError(a, b, c, want.u, want.v),
                                 GeometricNormal(a, b, c), light);
    TraversalOptions o = from_end;
    o.origin_tri = want.tri;
    const bool blocked = Occluded(*tree, s, o);
    shadow += OccludedLeafBvh(*tree, bvh, s, want.tri) != blocked;
    shadows += blocked;
    shadow_rays.push_back(s);
    shadow_origins.push_back(want.tri);
    shadow_blocked.push_back(blocked);
  }
  // Packets of 16 consecutive rays (coherent camera rows among them), each
  // lane against its single ray, bit for bit.
  int packets = PacketMismatches(*tree, bvh, rays);
  for (size_t i = 0; i < shadow_rays.size(); i += kRayPacketSize) {
    const int n = static_cast<int>(std::min<size_t>(kRayPacketSize, shadow_rays.size() - i));
    bool occluded[kRayPacketSize];
    OccludedPacketLeafBvh(*tree, bvh, &shadow_rays[i], n, &shadow_origins[i], occluded);
    for (int l = 0; l < n; ++l) packets += occluded[l] != (shadow_blocked[i + l] != 0);
  }
  EXPECT_EQ(closest, 0);
  EXPECT_EQ(any, 0);
  EXPECT_EQ(shadow, 0);
  EXPECT_EQ(packets, 0);
  // Each leaf slot's packet count (for the prefetch), 0 elsewhere.
  int bad_counts = 0;
  for (const LeafBvhNode& node : bvh.nodes) {
    for (int s = 0; s < kBvhWidth; ++s) {
      uint32_t want = 0;
      if (node.child[s] != LeafBvhNode::kNone && (node.child[s] & LeafBvhNode::kLeafBit)) {
        const float* p = tree->leaf_soa.data() +
                         static_cast<size_t>(node.child[s] & ~LeafBvhNode::kLeafBit) * kPacketFloats;
        for (uint32_t id0 = 0; !(id0 & kLastPacket); p += kPacketFloats, ++want) {
          std::memcpy(&id0, p + kPacketIds, sizeof(id0));
        }
      }
      bad_counts += node.packets[s] != std::min(want, 255u);
    }
  }
  EXPECT_EQ(bad_counts, 0);
  EXPECT_GT(hits, static_cast<int>(rays.size() / 40));
  std::printf("%s/%s: %zu rays, %d hits, %d shadow rays blocked, %zu nodes\n", scene.c_str(),
              preset.c_str(), rays.size(), hits, shadows, bvh.nodes.size());
}

INSTANTIATE_TEST_SUITE_P(
    AllPresets, LeafBvhVsKd,
    ::testing::Combine(::testing::Values("sphere", "voxels", "thin", "flat"),
                       ::testing::ValuesIn(AllPresetNames())),
    [](const ::testing::TestParamInfo<LeafBvhVsKd::ParamType>& info) {
      std::string name = absl::StrCat(std::get<0>(info.param), "_", std::get<1>(info.param));
      for (char& c : name) {
        if (c == '-') c = '_';
      }
      return name;
    });

// The packet kernel on every Highway target the machine runs (AVX-512's 16
// lanes, AVX2's two vectors of 8, SSE4's four of 4, ...).
TEST(LeafBvh, PacketsOnEveryTarget) {
  const TriangleSoup soup = MakeSoup("voxels");
  absl::StatusOr<KdTree> tree = BuildKdTree(soup, *Preset("sah-packet"));
  ASSERT_TRUE(tree.ok());
  const LeafBvh bvh = BuildLeafBvh(*tree);
  std::vector<Ray> rays = testing::CameraRays(soup, 64, 64);
  for (const Ray& r : testing::RandomRays(soup, 4000, 11)) rays.push_back(r);
  for (const Ray& r : AxisRays(1000, 13)) rays.push_back(r);
  for (const std::string& target : PacketKernelTargets()) {
    ScopedPacketKernelTarget scoped(target);
    ASSERT_TRUE(scoped.ok()) << target;
    EXPECT_EQ(PacketMismatches(*tree, bvh, rays), 0) << target;
  }
}

// Any-hit packets of one to five rays, so that from the root on a group has
// few lanes (the per-lane node test, FewLaneChildren), shadow rays leaving
// their origin triangle among them: each lane is the single ray's answer,
// on every target.
TEST(LeafBvh, FewRayAnyHitPacketsOnEveryTarget) {
  const TriangleSoup soup = MakeSoup("sphere");
  absl::StatusOr<KdTree> tree = BuildKdTree(soup, *Preset("sah-packet"));
  ASSERT_TRUE(tree.ok());
  const LeafBvh bvh = BuildLeafBvh(*tree);
  std::vector<Ray> rays = testing::CameraRays(soup, 48, 48);
  for (const Ray& r : testing::RandomRays(soup, 3000, 23)) rays.push_back(r);
  std::vector<uint32_t> origins(rays.size(), kNoHit);
  const Vec3 light = tree->bounds.hi + tree->bounds.Extent() * 0.5f;
  const size_t primary = rays.size();
  for (size_t i = 0; i < primary; ++i) {
    const Hit h = Intersect(*tree, rays[i]);
    if (!h.hit()) continue;
    const Vec3 &a = soup.a(h.tri), &b = soup.b(h.tri), &c = soup.c(h.tri);
    rays.push_back(
        SpawnShadowRay(HitPointWithError(a, b, c, h.u, h.v), GeometricNormal(a, b, c), light));
    origins.push_back(h.tri);
  }
  std::vector<bool> want(rays.size());
  int blocked = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    TraversalOptions o;
    o.from_end = true;
    o.origin_tri = origins[i];
    want[i] = Occluded(*tree, rays[i], o);
    blocked += want[i];
  }
  EXPECT_GT(blocked, 100);
  for (const std::string& target : PacketKernelTargets()) {
    ScopedPacketKernelTarget scoped(target);
    ASSERT_TRUE(scoped.ok()) << target;
    int bad = 0;
    for (size_t i = 0, n = 1; i < rays.size(); i += n, n = n % 5 + 1) {
      const int m = static_cast<int>(std::min(n, rays.size() - i));
      bool occluded[kRayPacketSize];
      OccludedPacketLeafBvh(*tree, bvh, &rays[i], m, &origins[i], occluded);
      for (int l = 0; l < m; ++l) bad += occluded[l] != want[i + l];
    }
    EXPECT_EQ(bad, 0) << target;
  }
}

// Counting (render_bench's packet_counts) leaves every answer as it is, and
// the counts add up: every ray counted, a node or leaf step carrying 1 to 16
// lanes, each lane's triangle tests within its leaves' steps.
TEST(LeafBvh, PacketCountsChangeNoAnswer) {
  const TriangleSoup soup = MakeSoup("sphere");
  absl::StatusOr<KdTree> tree = BuildKdTree(soup, *Preset("sah-packet"));
  ASSERT_TRUE(tree.ok());
  const LeafBvh bvh = BuildLeafBvh(*tree);
  std::vector<Ray> rays = testing::CameraRays(soup, 64, 64);
  for (const Ray& r : testing::RandomRays(soup, 4000, 17)) rays.push_back(r);
  PacketCounters closest, any;
  int bad = 0;
  for (size_t i = 0; i < rays.size(); i += kRayPacketSize) {
    const int n = static_cast<int>(std::min<size_t>(kRayPacketSize, rays.size() - i));
    Hit hits[kRayPacketSize], counted_hits[kRayPacketSize];
    bool occluded[kRayPacketSize], counted_occluded[kRayPacketSize];
    IntersectPacketLeafBvh(*tree, bvh, &rays[i], n, hits);
    IntersectPacketLeafBvh(*tree, bvh, &rays[i], n, counted_hits, &closest);
    OccludedPacketLeafBvh(*tree, bvh, &rays[i], n, nullptr, occluded);
    OccludedPacketLeafBvh(*tree, bvh, &rays[i], n, nullptr, counted_occluded, &any);
    for (int l = 0; l < n; ++l) {
      bad += !testing::BitwiseSameHit(hits[l], counted_hits[l]) +
             (occluded[l] != counted_occluded[l]);
    }
  }
  EXPECT_EQ(bad, 0);
  for (const PacketCounters* c : {&closest, &any}) {
    EXPECT_EQ(c->lanes.rays, rays.size());
    EXPECT_GT(c->packets, 0u);
    EXPECT_GE(c->groups, c->packets);
    EXPECT_GT(c->inner_steps, 0u);
    EXPECT_GT(c->leaf_steps, 0u);
    EXPECT_GE(c->lanes.inner_visits, c->inner_steps);
    EXPECT_LE(c->lanes.inner_visits, kRayPacketSize * c->inner_steps);
    EXPECT_GE(c->lanes.leaf_visits, c->leaf_steps);
    EXPECT_LE(c->lanes.leaf_visits, kRayPacketSize * c->leaf_steps);
    EXPECT_GT(c->triangle_steps, 0u);
    EXPECT_GE(c->lanes.triangle_tests, c->triangle_steps);
  }
}

// The packet kernel's slot filter (leaf_bvh_packet_kernel.cc SlotFilter)
// bounds each lane's widened slab distance by widening a bound on it; that
// is exact only if the widening t -/+ fl(|t| 4 u) never decreases as t
// grows: checked here for every finite float, from -max to +max.
TEST(LeafBvh, SlabWideningIsMonotone) {
  const volatile float pad = 4.0f * 0x1p-24f;  // the kernels' pad, not folded
  float prev_lo = -INFINITY, prev_hi = -INFINITY;
  int64_t bad = 0;
  for (int sign = 1; sign >= 0; --sign) {
    for (uint32_t k = 0; k < 0x7f800000u; ++k) {
      const uint32_t bits = sign ? (0x7f7fffffu - k) | 0x80000000u : k;
      float t;
      std::memcpy(&t, &bits, sizeof(t));
      const float lo = t - std::fabs(t) * pad, hi = t + std::fabs(t) * pad;
      bad += lo < prev_lo || hi < prev_hi;
      prev_lo = lo;
      prev_hi = hi;
    }
  }
  EXPECT_EQ(bad, 0);
}

TEST(LeafBvh, EmptyTreeAndMisses) {
  TriangleSoup soup;
  absl::StatusOr<KdTree> tree = BuildKdTree(soup, Config());
  ASSERT_TRUE(tree.ok());
  const LeafBvh bvh = BuildLeafBvh(*tree);
  EXPECT_TRUE(bvh.nodes.empty());
  Ray r;
  r.dir = Vec3(0, 0, 1);
  EXPECT_FALSE(IntersectLeafBvh(*tree, bvh, r).hit());
  EXPECT_FALSE(OccludedLeafBvh(*tree, bvh, r));
}

TEST(LeafBvh, SingleLeafAndBadRays) {
  TriangleSoup soup;
  soup.Add({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  absl::StatusOr<KdTree> tree = BuildKdTree(soup, Config());
  ASSERT_TRUE(tree.ok());
  const LeafBvh bvh = BuildLeafBvh(*tree);
  ASSERT_EQ(bvh.nodes.size(), 1u);
  Ray r;
  r.origin = Vec3(0.25f, 0.25f, 1);
  r.dir = Vec3(0, 0, -1);
  const Hit h = IntersectLeafBvh(*tree, bvh, r);
  EXPECT_EQ(h.tri, 0u);
  EXPECT_EQ(h.t, 1.0f);
  EXPECT_TRUE(OccludedLeafBvh(*tree, bvh, r));
  EXPECT_FALSE(OccludedLeafBvh(*tree, bvh, r, 0));  // its origin triangle
  r.dir = Vec3(NAN, 0, -1);
  EXPECT_FALSE(IntersectLeafBvh(*tree, bvh, r).hit());
  r.dir = Vec3(0, 0, 0);
  EXPECT_FALSE(OccludedLeafBvh(*tree, bvh, r));
}

}  // namespace
}  // namespace kdtree
