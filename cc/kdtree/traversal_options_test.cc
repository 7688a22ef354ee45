// The traversal's options (counting, any hit from the ray's end; traversal.h)
// against brute force, and the leaf packets' contents (leaf_layout.h).
// Every combination must give exactly the brute-force answer (closest hit:
// triangle, t, u, v; any hit: occlusion) on every ray.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "cc/kdtree/brute_force.h"
#include "cc/kdtree/builder.h"
#include "cc/kdtree/leaf_layout.h"
#include "cc/kdtree/stats.h"
#include "cc/kdtree/test_scenes.h"
#include "cc/kdtree/traversal.h"

namespace kdtree {
namespace {

TriangleSoup SceneByName(const std::string& name) {
  if (name == "sphere") return testing::BumpySphere(4, 3);
  if (name == "voxels") return testing::VoxelGrid(8, 6, 8, 5);
  return testing::ThinSoup(3000, 9);
}

// 4000 random rays (seeded) and a 64 x 64 camera's.
std::vector<Ray> TestRays(const TriangleSoup& soup, uint32_t seed) {
  std::vector<Ray> rays = testing::RandomRays(soup, 4000, seed);
  const std::vector<Ray> cam = testing::CameraRays(soup, 64, 64);
  rays.insert(rays.end(), cam.begin(), cam.end());
  return rays;
}

class Options : public ::testing::TestWithParam<std::tuple<std::string, std::string>> {};

TEST_P(Options, EveryCombinationEqualsBruteForce) {
  const auto& [scene, preset] = GetParam();
  const TriangleSoup soup = SceneByName(scene);
  absl::StatusOr<Config> config = Preset(preset);
  ASSERT_TRUE(config.ok());
  absl::StatusOr<KdTree> tree = BuildKdTree(soup, *config);
  ASSERT_TRUE(tree.ok()) << tree.status();
  const BruteForce bf(soup);
  const std::vector<Ray> rays = TestRays(soup, 23);
  int hits = 0, mismatches = 0;
  TraversalCounters counters;
  TraversalOptions end;
  end.from_end = true;
  for (const Ray& ray : rays) {
    const Hit want = bf.Intersect(ray);
    const Hit got = Intersect(*tree, ray);
    const Hit counted = Intersect(*tree, ray, {}, &counters);
    for (const Hit& h : {got, counted}) {
      if (h.tri != want.tri || (want.hit() && (h.t != want.t || h.u != want.u || h.v != want.v))) {
        ++mismatches;
      }
    }
    if (Occluded(*tree, ray) != want.hit()) ++mismatches;
    // From the ray's end: the same answer (and the counting path too).
    TraversalCounters end_counters;
    if (Occluded(*tree, ray, end) != want.hit()) ++mismatches;
    if (Occluded(*tree, ray, end, &end_counters) != want.hit()) ++mismatches;
    hits += want.hit();
  }
  EXPECT_EQ(mismatches, 0) << scene << " " << preset;
  EXPECT_GT(hits, 0);
  EXPECT_EQ(counters.rays, rays.size());
}

// The fast test (Moeller-Trumbore) on the same traversal: the counting path
// gives the fast path's hit bit for bit, and any hit, front to back or from
// the ray's end, counted or not, agrees with it. (Against brute force the
// fast test is checked in traversal_test, within its rounding.)
TEST_P(Options, FastTestEveryCombinationAgrees) {
  const auto& [scene, preset] = GetParam();
  const TriangleSoup soup = SceneByName(scene);
  absl::StatusOr<KdTree> tree = BuildKdTree(soup, *Preset(preset));
  ASSERT_TRUE(tree.ok()) << tree.status();
  const std::vector<Ray> rays = TestRays(soup, 29);
  const TraversalOptions fast = WithTest(IntersectionMode::kFast);
  TraversalOptions end = fast;
  end.from_end = true;
  int hits = 0, mismatches = 0;
  for (const Ray& ray : rays) {
    TraversalCounters counters;
    const Hit want = Intersect(*tree, ray, fast);
    hits += want.hit();
    if (!testing::BitwiseSameHit(Intersect(*tree, ray, fast, &counters), want)) ++mismatches;
    for (const TraversalOptions& o : {fast, end}) {
      if (Occluded(*tree, ray, o) != want.hit()) ++mismatches;
      if (Occluded(*tree, ray, o, &counters) != want.hit()) ++mismatches;
    }
  }
  EXPECT_EQ(mismatches, 0) << scene << " " << preset;
  EXPECT_GT(hits, 0);
}

INSTANTIATE_TEST_SUITE_P(All, Options,
                         ::testing::Combine(::testing::Values("sphere", "voxels", "thin"),
                                            ::testing::Values("median-24-8", "binning-8",
                                                              "clipping", "clipping-pruning")),
                         [](const auto& info) {
                           std::string n = std::get<0>(info.param) + "_" + std::get<1>(info.param);
                           for (char& c : n) c = c == '-' ? '_' : c;
                           return n;
                         });

// Each leaf's packets: the soup's vertices of its triangles, lane by lane,
// kLastPacket on lane 0 of the last packet only, pads (kPadLane, zero
// vertices) only after the last triangle; and the triangles the packets hold
// are the references the statistics count.
TEST(LeafLayout, PacketsHoldEachLeafsVerticesInOrder) {
  const TriangleSoup soup = testing::BumpySphere(2, 1);
  absl::StatusOr<KdTree> tree = BuildKdTree(soup, *Preset("clipping-pruning"));
  ASSERT_TRUE(tree.ok());
  size_t checked = 0, empty = 0, refs = 0;
  for (const KdNode& node : tree->nodes) {
    if (!node.is_leaf()) continue;
    if (node.index() == kEmptyLeaf) {
      EXPECT_EQ(LeafTriangleCount(*tree, node), 0u);
      ++empty;
      continue;
    }
    const std::vector<uint32_t> tris = LeafTriangles(*tree, node);
    ASSERT_FALSE(tris.empty());
    EXPECT_EQ(LeafTriangleCount(*tree, node), tris.size());
    refs += tris.size();
    const uint32_t packets = (tris.size() + kPacketLanes - 1) / kPacketLanes;
    for (uint32_t j = 0; j < packets * kPacketLanes; ++j) {
      const size_t at = (node.index() + j / kPacketLanes) * size_t{kPacketFloats};
      const float* packet = &tree->leaf_soa[at];
      const int lane = j % kPacketLanes;
      uint32_t id;
      std::memcpy(&id, &packet[kPacketIds + lane], sizeof(id));
      const bool last = j / kPacketLanes + 1 == packets;
      if (lane == 0) {
        EXPECT_EQ((id & kLastPacket) != 0, last);
        id &= ~kLastPacket;
      }
      if (j >= tris.size()) {
        EXPECT_EQ(id, kPadLane);
        for (int f = 0; f < 9; ++f) EXPECT_EQ(packet[f * kPacketLanes + lane], 0.0f);
        continue;
      }
      EXPECT_EQ(id, tris[j]);
      ASSERT_LT(id, soup.size());
      for (int v = 0; v < 3; ++v) {
        const Vec3& p = soup.v[3 * id + v];
        EXPECT_EQ(packet[(3 * v + 0) * kPacketLanes + lane], p.x);
        EXPECT_EQ(packet[(3 * v + 1) * kPacketLanes + lane], p.y);
        EXPECT_EQ(packet[(3 * v + 2) * kPacketLanes + lane], p.z);
        ++checked;
      }
    }
  }
  EXPECT_GT(empty, 0u);
  EXPECT_GT(checked, soup.size());
  EXPECT_EQ(refs, ComputeStats(*tree).leaf_refs);
  EXPECT_EQ(tree->num_triangles(), soup.size());
  EXPECT_GT(LeafLayoutBytes(*tree), 0u);
}

}  // namespace
}  // namespace kdtree
