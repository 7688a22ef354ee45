// The traversal's speed options (leaf layout in packets of 4, mailboxing, any
// hit from the ray's end; traversal.h, leaf_layout.h) against brute force, and
// the layout's contents.
// Every combination must give exactly the brute-force answer (closest hit:
// triangle, t, u, v; any hit: occlusion) on every ray.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "cc/kdtree/brute_force.h"
#include "cc/kdtree/builder.h"
#include "cc/kdtree/leaf_layout.h"
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
  ASSERT_TRUE(HasLeafLayout(*tree));
  KdTree plain = *tree;  // the same tree without the layout: vertices by index
  DropLeafLayout(&plain);
  ASSERT_FALSE(HasLeafLayout(plain));
  const BruteForce bf(soup);
  const std::vector<Ray> rays = TestRays(soup, 23);
  int hits = 0;
  uint64_t tests_plain = 0, tests_mailbox = 0;
  for (const KdTree* t : {&*tree, &plain}) {
    for (bool mailbox : {false, true}) {
      TraversalOptions opt;
      opt.mailbox = mailbox;
      TraversalCounters counters;
      int mismatches = 0;
      for (const Ray& ray : rays) {
        const Hit want = bf.Intersect(ray);
        const Hit got = Intersect(*t, ray, opt);
        const Hit counted = Intersect(*t, ray, opt, &counters);
        for (const Hit& h : {got, counted}) {
          if (h.tri != want.tri || (want.hit() && (h.t != want.t || h.u != want.u || h.v != want.v))) {
            ++mismatches;
          }
        }
        if (Occluded(*t, ray, opt) != want.hit()) ++mismatches;
        // From the ray's end: the same answer (and the counting path too).
        TraversalOptions end = opt;
        end.from_end = true;
        TraversalCounters end_counters;
        if (Occluded(*t, ray, end) != want.hit()) ++mismatches;
        if (Occluded(*t, ray, end, &end_counters) != want.hit()) ++mismatches;
        hits += want.hit();
      }
      EXPECT_EQ(mismatches, 0) << scene << " " << preset << (t == &plain ? " by index" : " packets")
                               << (mailbox ? " mailbox" : "");
      (mailbox ? tests_mailbox : tests_plain) += counters.triangle_tests;
    }
  }
  EXPECT_GT(hits, 0);
  // Mailboxing never adds a test; with clipping (references in several leaves)
  // it removes some.
  EXPECT_LE(tests_mailbox, tests_plain);
  if (config->use_clipping) {
    EXPECT_LT(tests_mailbox, tests_plain);
  }
}

// The fast test reads the same leaf packets (lane_fast_test-inl.h) and must
// answer as it does by index, bit for bit: closest hit (triangle, t, u, v)
// and any hit from either end, with and without the mailbox. (Against brute
// force the fast test is checked in traversal_test, within its rounding.)
TEST_P(Options, FastTestOnThePacketsEqualsItByIndex) {
  const auto& [scene, preset] = GetParam();
  const TriangleSoup soup = SceneByName(scene);
  absl::StatusOr<KdTree> tree = BuildKdTree(soup, *Preset(preset));
  ASSERT_TRUE(tree.ok()) << tree.status();
  ASSERT_TRUE(HasLeafLayout(*tree));
  KdTree plain = *tree;
  DropLeafLayout(&plain);
  const std::vector<Ray> rays = TestRays(soup, 29);
  int hits = 0, mismatches = 0;
  for (bool mailbox : {false, true}) {
    TraversalOptions opt = WithTest(IntersectionMode::kFast);
    opt.mailbox = mailbox;
    TraversalOptions end = opt;
    end.from_end = true;
    TraversalCounters packed_counters, plain_counters;
    for (const Ray& ray : rays) {
      const Hit want = Intersect(plain, ray, opt, &plain_counters);
      const Hit got = Intersect(*tree, ray, opt, &packed_counters);
      hits += want.hit();
      const Hit fast_path = Intersect(*tree, ray, opt);  // not counting
      if (!testing::BitwiseSameHit(got, want)) ++mismatches;
      if (!testing::BitwiseSameHit(fast_path, want)) ++mismatches;
      if (Occluded(*tree, ray, opt) != want.hit()) ++mismatches;
      if (Occluded(*tree, ray, end) != want.hit()) ++mismatches;
    }
    // The same nodes and the same triangle tests.
    EXPECT_EQ(packed_counters.inner_visits, plain_counters.inner_visits);
    EXPECT_EQ(packed_counters.triangle_tests, plain_counters.triangle_tests);
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

TEST(LeafLayout, PacketsHoldEachLeafsVerticesInOrder) {
  const TriangleSoup soup = testing::BumpySphere(2, 1);
  absl::StatusOr<KdTree> tree = BuildKdTree(soup, *Preset("clipping-pruning"));
  ASSERT_TRUE(tree.ok());
  ASSERT_TRUE(HasLeafLayout(*tree));
  size_t checked = 0, empty = 0;
  for (size_t n = 0; n < tree->nodes.size(); ++n) {
    const KdNode& node = tree->nodes[n];
    ASSERT_EQ(node.is_leaf(), tree->leaf_nodes[n].is_leaf());
    if (!node.is_leaf()) {
      EXPECT_EQ(tree->leaf_nodes[n].bits, node.bits);  // inner nodes unchanged
      EXPECT_EQ(tree->leaf_nodes[n].split, node.split);
      continue;
    }
    const uint32_t count = tree->LeafCount(node);
    if (count == 0) {
      EXPECT_EQ(tree->leaf_nodes[n].index(), kEmptyLeaf);
      ++empty;
      continue;
    }
    const uint32_t first = tree->leaf_nodes[n].index();
    const uint32_t packets = (count + kPacketLanes - 1) / kPacketLanes;
    for (uint32_t j = 0; j < packets * kPacketLanes; ++j) {
      const float* packet = &tree->leaf_soa[(first + j / kPacketLanes) * size_t{kPacketFloats}];
      const int lane = j % kPacketLanes;
      uint32_t id;
      std::memcpy(&id, &packet[kPacketIds + lane], sizeof(id));
      const bool last = j / kPacketLanes + 1 == packets;
      if (lane == 0) {
        EXPECT_EQ((id & kLastPacket) != 0, last);
        id &= ~kLastPacket;
      }
      if (j >= count) {
        EXPECT_EQ(id, kPadLane);
        continue;
      }
      const uint32_t tri = tree->LeafBegin(node)[j];
      EXPECT_EQ(id, tri);
      for (int v = 0; v < 3; ++v) {
        const Vec3& p = soup.v[3 * tri + v];
        EXPECT_EQ(packet[(3 * v + 0) * kPacketLanes + lane], p.x);
        EXPECT_EQ(packet[(3 * v + 1) * kPacketLanes + lane], p.y);
        EXPECT_EQ(packet[(3 * v + 2) * kPacketLanes + lane], p.z);
        ++checked;
      }
    }
  }
  EXPECT_GT(empty, 0u);
  EXPECT_GT(checked, soup.size());
  EXPECT_GT(LeafLayoutBytes(*tree), 0u);
}

}  // namespace
}  // namespace kdtree
