// The BVH over whole triangles (triangle_bvh.h), traced by the leaf-BVH
// kernels, against the kd-tree's own traversal, bit for bit (bvh_check.h:
// closest and any hits, shadow rays that leave their origin triangle
// untested, single rays and packets), with seeded random rays, a camera,
// axis-parallel rays on the voxel grid's planes, and rays at vertices and
// edges, one in four against brute force too; and its structure (every kept
// triangle in one leaf, boxes that hold their triangles).
#include "cc/kdtree/triangle_bvh.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "cc/kdtree/brute_force.h"
#include "cc/kdtree/builder.h"
#include "cc/kdtree/bvh_check.h"
#include "cc/kdtree/leaf_layout.h"
#include "cc/kdtree/test_scenes.h"
#include "gtest/gtest.h"

namespace kdtree {
namespace {

// Rays from random points around the soup aimed at its triangles'
// vertices and edge midpoints, where a watertight test is hardest.
std::vector<Ray> VertexAndEdgeRays(const TriangleSoup& soup, int count, uint32_t seed) {
  std::mt19937 rng(seed);
  const AABB box = soup.Bounds();
  std::uniform_real_distribution<float> unit(-0.5f, 1.5f);
  std::uniform_int_distribution<size_t> tri(0, soup.size() - 1);
  std::uniform_int_distribution<int> which(0, 5);
  std::vector<Ray> rays;
  for (int i = 0; i < count; ++i) {
    const size_t t = tri(rng);
    const Vec3 v[3] = {soup.a(t), soup.b(t), soup.c(t)};
    const int w = which(rng);
    const Vec3 target = w < 3 ? v[w] : (v[w - 3] + v[(w - 2) % 3]) * 0.5f;
    Ray r;
    for (int k = 0; k < 3; ++k) r.origin[k] = box.lo[k] + unit(rng) * (box.hi[k] - box.lo[k]);
    r.dir = target - r.origin;
    rays.push_back(r);
  }
  return rays;
}

// The triangles of the leaf whose first packet is `first`.
std::vector<uint32_t> LeafIds(const KdTree& leaves, uint32_t first) {
  std::vector<uint32_t> ids;
  ForEachPacketLane(leaves.leaf_soa.data() + static_cast<size_t>(first) * kPacketFloats,
                    [&](const float*, int, uint32_t t) { ids.push_back(t); });
  return ids;
}

class TriangleBvhVsKd : public ::testing::TestWithParam<std::string> {};

TEST_P(TriangleBvhVsKd, SameAnswers) {
  const TriangleSoup soup = testing::NamedScene(GetParam());
  absl::StatusOr<KdTree> tree = BuildKdTree(soup, *Preset("sah-packet"));
  ASSERT_TRUE(tree.ok()) << tree.status();
  absl::StatusOr<LeafBvh> built = BuildTriangleBvh(soup);
  ASSERT_TRUE(built.ok()) << built.status();
  const LeafBvh& tb = *built;
  ASSERT_FALSE(tb.nodes.empty());
  std::vector<Ray> rays = testing::RandomRays(soup, 20000, 7);
  for (const Ray& r : testing::CameraRays(soup, 120, 120)) rays.push_back(r);
  for (const Ray& r : testing::GridAxisRays(3000, 9)) rays.push_back(r);
  for (const Ray& r : VertexAndEdgeRays(soup, 6000, 5)) rays.push_back(r);
  const testing::BvhMismatches m =
      testing::CompareWithKdTree(soup, *tree, tb, rays, 4);
  EXPECT_EQ(m.closest, 0);
  EXPECT_EQ(m.any, 0);
  EXPECT_EQ(m.shadow, 0);
  EXPECT_EQ(m.packets, 0);
  EXPECT_GT(m.hits, static_cast<int>(rays.size() / 40));
}

INSTANTIATE_TEST_SUITE_P(Scenes, TriangleBvhVsKd,
                         ::testing::Values("sphere", "voxels", "thin", "flat"));

// Every triangle in exactly one leaf, in a slot whose box holds it whole;
// the slots' packet counts right.
TEST(TriangleBvh, EachTriangleOnceInsideItsBox) {
  const TriangleSoup soup = testing::NamedScene("thin");
  absl::StatusOr<LeafBvh> built = BuildTriangleBvh(soup);
  ASSERT_TRUE(built.ok()) << built.status();
  const LeafBvh& tb = *built;
  EXPECT_EQ(tb.leaves.triangles, soup.size());
  EXPECT_TRUE(tb.leaves.nodes.empty());
  std::vector<int> seen(soup.size(), 0);
  int outside = 0, bad_counts = 0;
  for (const LeafBvhNode& node : tb.nodes) {
    for (int s = 0; s < kBvhWidth; ++s) {
      if (node.child[s] == LeafBvhNode::kNone || !(node.child[s] & LeafBvhNode::kLeafBit)) continue;
      const std::vector<uint32_t> ids = LeafIds(tb.leaves, node.child[s] & ~LeafBvhNode::kLeafBit);
      bad_counts += node.packets[s] != (ids.size() + kPacketLanes - 1) / kPacketLanes;
      for (uint32_t t : ids) {
        ++seen[t];
        for (const Vec3& v : {soup.a(t), soup.b(t), soup.c(t)}) {
          for (int k = 0; k < 3; ++k) {
            outside += !(v[k] >= node.box[k][s] && v[k] <= node.box[3 + k][s]);
          }
        }
      }
    }
  }
  for (size_t t = 0; t < soup.size(); ++t) EXPECT_EQ(seen[t], 1) << t;
  EXPECT_EQ(outside, 0);
  EXPECT_EQ(bad_counts, 0);
}

// Bad input, as BuildKdTree refuses it: a non-finite vertex, named.
TEST(TriangleBvh, RefusesNonFiniteVertices) {
  for (float bad : {std::numeric_limits<float>::quiet_NaN(), INFINITY}) {
    TriangleSoup soup = testing::NamedScene("thin");
    soup.Add(Vec3(0, 0, 0), Vec3(bad, 0, 0), Vec3(0, 1, 0));
    absl::StatusOr<LeafBvh> built = BuildTriangleBvh(soup);
    ASSERT_FALSE(built.ok());
    EXPECT_EQ(built.status().code(), absl::StatusCode::kInvalidArgument);
    EXPECT_NE(built.status().message().find("triangle 2000"), std::string::npos)
        << built.status();
  }
  TriangleSoup ragged;
  ragged.v = {Vec3(0, 0, 0), Vec3(1, 0, 0)};
  EXPECT_FALSE(BuildTriangleBvh(ragged).ok());
}

// One triangle, and none: a one-slot root, and an empty hierarchy that
// every ray misses.
TEST(TriangleBvh, TinySoups) {
  TriangleSoup one;
  one.Add(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0));
  const LeafBvh tb = *BuildTriangleBvh(one);
  ASSERT_EQ(tb.nodes.size(), 1u);
  const Hit h = IntersectLeafBvh(tb, Ray{{0.2f, 0.2f, 1}, {0, 0, -1}});
  EXPECT_EQ(h.tri, 0u);
  const LeafBvh none = *BuildTriangleBvh(TriangleSoup());
  EXPECT_TRUE(none.nodes.empty());
  EXPECT_FALSE(IntersectLeafBvh(none, Ray{{0, 0, 1}, {0, 0, -1}}).hit());
}

// Coordinates near the largest float, whose extents overflow a float: rays
// still get brute force's answers.
TEST(TriangleBvh, HugeCoordinates) {
  TriangleSoup soup;
  const float big = 3e38f;
  for (int i = 0; i < 12; ++i) {
    const float x = (i % 2 ? big : -big) * (0.5f + 0.04f * static_cast<float>(i));
    soup.Add(Vec3(x, 0, 0), Vec3(x, 1, 0), Vec3(x, 0, 1));
  }
  const LeafBvh tb = *BuildTriangleBvh(soup);
  ASSERT_FALSE(tb.nodes.empty());
  const BruteForce bf(soup);
  int bad = 0;
  for (int i = 0; i < 12; ++i) {
    const Vec3 target(soup.a(i).x, 0.25f, 0.25f);
    for (const Vec3& from : {Vec3(0, 0.25f, 0.25f), Vec3(target.x * 0.5f, 0.3f, 0.2f)}) {
      const Ray r{from, target - from};
      bad += !testing::BitwiseSameHit(IntersectLeafBvh(tb, r), bf.Intersect(r));
    }
  }
  EXPECT_EQ(bad, 0);
}

}  // namespace
}  // namespace kdtree
