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
#include <limits>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "cc/kdtree/builder.h"
#include "cc/kdtree/bvh_check.h"
#include "cc/kdtree/leaf_layout.h"
#include "cc/kdtree/ray_packet.h"
#include "cc/kdtree/test_scenes.h"
#include "cc/kdtree/traversal.h"
#include "gtest/gtest.h"

namespace kdtree {
namespace {

// BuildLeafBvh's hierarchy, which without a budget always builds.
LeafBvh Built(const KdTree& tree) {
  absl::StatusOr<LeafBvh> bvh = BuildLeafBvh(tree);
  EXPECT_TRUE(bvh.ok()) << bvh.status();
  return bvh.ok() ? *std::move(bvh) : LeafBvh();
}

class LeafBvhVsKd : public ::testing::TestWithParam<std::tuple<std::string, std::string>> {};

TEST_P(LeafBvhVsKd, SameAnswers) {
  const auto& [scene, preset] = GetParam();
  const TriangleSoup soup = testing::NamedScene(scene);
  absl::StatusOr<Config> config = Preset(preset);
  ASSERT_TRUE(config.ok());
  absl::StatusOr<KdTree> tree = BuildKdTree(soup, *config);
  ASSERT_TRUE(tree.ok()) << tree.status();
  const LeafBvh bvh = Built(*tree);
  ASSERT_FALSE(bvh.nodes.empty());
  std::vector<Ray> rays = testing::RandomRays(soup, 20000, 7);
  for (const Ray& r : testing::CameraRays(soup, 120, 120)) rays.push_back(r);
  for (const Ray& r : testing::GridAxisRays(3000, 9)) rays.push_back(r);
  // Rays that start behind their origin (tmin < 0: the box test's widening
  // in full, slab_slots-inl.h), ahead of it, or at -0: random ones and
  // axis-parallel ones (the set-up's path for a zero direction component).
  const float size = Length(soup.Bounds().Extent());
  std::vector<Ray> moved(rays.begin(), rays.begin() + 4000);
  for (const Ray& r : testing::GridAxisRays(1500, 13)) moved.push_back(r);
  for (size_t i = 0; i < moved.size(); ++i) {
    moved[i].tmin = (i % 3 == 0 ? -0.5f : i % 3 == 1 ? 0.1f : -0.0f) * size;
    rays.push_back(moved[i]);
  }
  const testing::BvhMismatches m = testing::CompareWithKdTree(soup, *tree, bvh, rays, 16);
  EXPECT_EQ(m.closest, 0);
  EXPECT_EQ(m.any, 0);
  EXPECT_EQ(m.shadow, 0);
  EXPECT_EQ(m.packets, 0);
  // Each leaf slot's packet count (for the prefetch), 0 elsewhere.
  int bad_counts = 0;
  for (const LeafBvhNode& node : bvh.nodes) {
    for (int s = 0; s < kBvhWidth; ++s) {
      uint32_t want = 0;
      if (node.child[s] != LeafBvhNode::kNone && (node.child[s] & LeafBvhNode::kLeafBit)) {
        const float* p = bvh.leaves.leaf_soa.data() +
                         static_cast<size_t>(node.child[s] & ~LeafBvhNode::kLeafBit) * kPacketFloats;
        for (uint32_t id0 = 0; !(id0 & kLastPacket); p += kPacketFloats, ++want) {
          std::memcpy(&id0, p + kPacketIds, sizeof(id0));
        }
      }
      bad_counts += node.packets[s] != std::min(want, 255u);
    }
  }
  EXPECT_EQ(bad_counts, 0);
  EXPECT_GT(m.hits, static_cast<int>(rays.size() / 40));
  std::printf("%s/%s: %zu rays, %d hits, %d shadow rays blocked, %zu nodes\n", scene.c_str(),
              preset.c_str(), rays.size(), m.hits, m.shadows, bvh.nodes.size());
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
  const TriangleSoup soup = testing::NamedScene("voxels");
  absl::StatusOr<KdTree> tree = BuildKdTree(soup, *Preset("sah-packet"));
  ASSERT_TRUE(tree.ok());
  const LeafBvh bvh = Built(*tree);
  std::vector<Ray> rays = testing::CameraRays(soup, 64, 64);
  for (const Ray& r : testing::RandomRays(soup, 4000, 11)) rays.push_back(r);
  for (const Ray& r : testing::GridAxisRays(1000, 13)) rays.push_back(r);
  for (const std::string& target : PacketKernelTargets()) {
    ScopedPacketKernelTarget scoped(target);
    ASSERT_TRUE(scoped.ok()) << target;
    EXPECT_EQ(testing::PacketMismatches(*tree, bvh, rays), 0) << target;
  }
}

// Any-hit packets of one to five rays, so that from the root on a group has
// few lanes (the per-lane node test, FewLaneChildren), shadow rays leaving
// their origin triangle among them: each lane is the single ray's answer,
// on every target.
TEST(LeafBvh, FewRayAnyHitPacketsOnEveryTarget) {
  const TriangleSoup soup = testing::NamedScene("sphere");
  absl::StatusOr<KdTree> tree = BuildKdTree(soup, *Preset("sah-packet"));
  ASSERT_TRUE(tree.ok());
  const LeafBvh bvh = Built(*tree);
  std::vector<Ray> rays = testing::CameraRays(soup, 48, 48);
  for (const Ray& r : testing::RandomRays(soup, 3000, 23)) rays.push_back(r);
  std::vector<uint32_t> origins(rays.size(), kNoHit);
  const Vec3 light = tree->bounds.hi + tree->bounds.Extent() * 0.5f;
  const size_t primary = rays.size();
  for (size_t i = 0; i < primary; ++i) {
    const Hit h = Intersect(*tree, rays[i]);
    if (!h.hit()) continue;
    rays.push_back(testing::ShadowRayFromHit(soup, h, light));
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
      OccludedPacketLeafBvh(bvh, &rays[i], m, &origins[i], occluded);
      for (int l = 0; l < m; ++l) bad += occluded[l] != want[i + l];
    }
    EXPECT_EQ(bad, 0) << target;
  }
}

// Counting (render_bench's packet_counts) leaves every answer as it is, and
// the counts add up: every ray counted, a node or leaf step carrying 1 to 16
// lanes, each lane's triangle tests within its leaves' steps.
TEST(LeafBvh, PacketCountsChangeNoAnswer) {
  const TriangleSoup soup = testing::NamedScene("sphere");
  absl::StatusOr<KdTree> tree = BuildKdTree(soup, *Preset("sah-packet"));
  ASSERT_TRUE(tree.ok());
  const LeafBvh bvh = Built(*tree);
  std::vector<Ray> rays = testing::CameraRays(soup, 64, 64);
  for (const Ray& r : testing::RandomRays(soup, 4000, 17)) rays.push_back(r);
  PacketCounters closest, any;
  int bad = 0;
  for (size_t i = 0; i < rays.size(); i += kRayPacketSize) {
    const int n = static_cast<int>(std::min<size_t>(kRayPacketSize, rays.size() - i));
    Hit hits[kRayPacketSize], counted_hits[kRayPacketSize];
    bool occluded[kRayPacketSize], counted_occluded[kRayPacketSize];
    IntersectPacketLeafBvh(bvh, &rays[i], n, hits);
    IntersectPacketLeafBvh(bvh, &rays[i], n, counted_hits, &closest);
    OccludedPacketLeafBvh(bvh, &rays[i], n, nullptr, occluded);
    OccludedPacketLeafBvh(bvh, &rays[i], n, nullptr, counted_occluded, &any);
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

// The single rays' widening for tmin >= 0 (slab_slots-inl.h RaySlots,
// kScaled): t * (1 -+ 4 u) is t -+ fl(|t| 4 u) bit for bit wherever |t| 4 u
// is a normal float (t >= 2^-104), and everywhere t (1 -+ 4 u) correctly
// rounded; checked on every 13th non-negative float and the edges.
TEST(LeafBvh, ScaledWideningIsTheSameNumbers) {
  const volatile float pad = 4.0f * 0x1p-24f;  // not folded
  const volatile float lo_scale = 1.0f - 4.0f * 0x1p-24f, hi_scale = 1.0f + 4.0f * 0x1p-24f;
  int64_t bad = 0, same = 0;
  const auto check = [&](float t) {
    const float lo = t * lo_scale, hi = t * hi_scale;
    // The exact products fit a double (24 + 23 bits): one rounding to float.
    bad += lo != static_cast<float>(static_cast<double>(t) * (1.0 - 0x1p-22));
    bad += hi != static_cast<float>(static_cast<double>(t) * (1.0 + 0x1p-22));
    if (t >= 0x1p-104f) {
      const float old_lo = t - std::fabs(t) * pad, old_hi = t + std::fabs(t) * pad;
      bad += std::memcmp(&lo, &old_lo, sizeof(lo)) != 0;
      bad += std::memcmp(&hi, &old_hi, sizeof(hi)) != 0;
      ++same;
    }
  };
  for (uint32_t bits = 0; bits < 0x7f800000u; bits += 13) {
    float t;
    std::memcpy(&t, &bits, sizeof(t));
    check(t);
  }
  for (const float t : {0.0f, 0x1p-149f, 0x1p-126f, 0x1p-104f, std::nextafter(0x1p-104f, 0.0f),
                        1.0f, std::numeric_limits<float>::max()}) {
    check(t);
  }
  EXPECT_EQ(bad, 0);
  EXPECT_GT(same, 100000000);
}

// The triangle ids of the packets at `soa`, pads left out.
std::vector<uint32_t> PacketIds(const float* soa, size_t floats) {
  std::vector<uint32_t> ids;
  for (size_t i = 0; i < floats; i += kPacketFloats) {
    for (int l = 0; l < kPacketLanes; ++l) {
      uint32_t id;
      std::memcpy(&id, soa + i + kPacketIds + l, sizeof(id));
      if (l == 0) id &= ~kLastPacket;
      if (id != (kPadLane & ~kLastPacket) && id != kPadLane) ids.push_back(id);
    }
  }
  std::sort(ids.begin(), ids.end());
  return ids;
}

// Each BVH leaf holds one kd leaf's triangles flat on one axis-aligned plane,
// or its triangles flat on none; together they hold the tree's references.
TEST(LeafBvh, FlatGroups) {
  const TriangleSoup soup = testing::NamedScene("voxels");
  absl::StatusOr<KdTree> tree = BuildKdTree(soup, *Preset("sah-packet"));
  ASSERT_TRUE(tree.ok());
  const LeafBvh bvh = Built(*tree);
  EXPECT_EQ(PacketIds(bvh.leaves.leaf_soa.data(), bvh.leaves.leaf_soa.size()),
            PacketIds(tree->leaf_soa.data(), tree->leaf_soa.size()));
  int leaves = 0, flat = 0, mixed = 0;
  for (const LeafBvhNode& node : bvh.nodes) {
    for (int s = 0; s < kBvhWidth; ++s) {
      if (node.child[s] == LeafBvhNode::kNone || !(node.child[s] & LeafBvhNode::kLeafBit)) continue;
      ++leaves;
      const float* p = bvh.leaves.leaf_soa.data() +
                       static_cast<size_t>(node.child[s] & ~LeafBvhNode::kLeafBit) * kPacketFloats;
      int plane_axis = -2;
      float plane = 0;
      bool same = true;
      ForEachPacketLane(p, [&](const float* packet, int l, uint32_t) {
        Vec3 v[3];
        PacketTriangle(packet, l, &v[0], &v[1], &v[2]);
        int axis = -1;
        for (int k = 2; k >= 0; --k) {
          if (v[0][k] == v[1][k] && v[1][k] == v[2][k]) axis = k;
        }
        if (plane_axis == -2) {
          plane_axis = axis;
          plane = axis >= 0 ? v[0][axis] : 0;
        }
        same &= axis == plane_axis && (axis < 0 || v[0][axis] == plane);
      });
      flat += plane_axis >= 0;
      mixed += !same;
    }
  }
  EXPECT_EQ(mixed, 0);
  EXPECT_GT(flat, leaves / 2);  // the voxels' faces are all flat
  // Its packets' bytes, counted without the build (for kdrt's budget).
  EXPECT_EQ(LeafBvhPacketBytes(*tree), bvh.packet_bytes());
  const TriangleSoup sphere = testing::NamedScene("sphere");
  absl::StatusOr<KdTree> round = BuildKdTree(sphere, *Preset("sah-packet"));
  ASSERT_TRUE(round.ok());
  EXPECT_EQ(LeafBvhPacketBytes(*round), Built(*round).packet_bytes());
  // A budget one byte short of the packets: refused, saying why.
  const uint64_t bytes = LeafBvhPacketBytes(*tree);
  absl::StatusOr<LeafBvh> short_of = BuildLeafBvh(*tree, bytes - 1);
  ASSERT_FALSE(short_of.ok());
  EXPECT_EQ(short_of.status().code(), absl::StatusCode::kResourceExhausted);
  EXPECT_NE(short_of.status().message().find("the BVH over the tree's leaves"), std::string::npos);
  absl::StatusOr<LeafBvh> exact = BuildLeafBvh(*tree, bytes);
  ASSERT_TRUE(exact.ok()) << exact.status();
  EXPECT_EQ(exact->packet_bytes(), bytes);
}

TEST(LeafBvh, EmptyTreeAndMisses) {
  TriangleSoup soup;
  absl::StatusOr<KdTree> tree = BuildKdTree(soup, Config());
  ASSERT_TRUE(tree.ok());
  const LeafBvh bvh = Built(*tree);
  EXPECT_TRUE(bvh.nodes.empty());
  Ray r;
  r.dir = Vec3(0, 0, 1);
  EXPECT_FALSE(IntersectLeafBvh(bvh, r).hit());
  EXPECT_FALSE(OccludedLeafBvh(bvh, r));
}

TEST(LeafBvh, SingleLeafAndBadRays) {
  TriangleSoup soup;
  soup.Add({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  absl::StatusOr<KdTree> tree = BuildKdTree(soup, Config());
  ASSERT_TRUE(tree.ok());
  const LeafBvh bvh = Built(*tree);
  ASSERT_EQ(bvh.nodes.size(), 1u);
  Ray r;
  r.origin = Vec3(0.25f, 0.25f, 1);
  r.dir = Vec3(0, 0, -1);
  const Hit h = IntersectLeafBvh(bvh, r);
  EXPECT_EQ(h.tri, 0u);
  EXPECT_EQ(h.t, 1.0f);
  EXPECT_TRUE(OccludedLeafBvh(bvh, r));
  EXPECT_FALSE(OccludedLeafBvh(bvh, r, 0));  // its origin triangle
  r.dir = Vec3(NAN, 0, -1);
  EXPECT_FALSE(IntersectLeafBvh(bvh, r).hit());
  r.dir = Vec3(0, 0, 0);
  EXPECT_FALSE(OccludedLeafBvh(bvh, r));
}

}  // namespace
}  // namespace kdtree
