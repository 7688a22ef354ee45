#include "cc/kdtree/stats.h"

#include <cmath>
#include <string>
#include <vector>

#include "cc/kdtree/builder.h"
#include "cc/kdtree/leaf_layout.h"
#include "gtest/gtest.h"
#include "nlohmann/json.hpp"

namespace kdtree {
namespace {

// Three unit triangles along x at [0,1], [3,4] and [7,8] (y, z in [0, 1]),
// spatial median, maxLeafSize 1. Counted by hand:
//   root box x [0, 8] splits at x = 4: left {T0, T1} (T1's box ends at 4, so
//   it only touches the plane and goes left), right {T2} -> leaf at depth 1;
//   left box x [0, 4] splits at x = 2: {T0} and {T1} -> leaves at depth 2.
// N_I = 2, N_L = 3, N_TP = 3, no empty leaf, D_max = 2, D_avg = 5/3.
// mem = (8 * 5 + 4 * (3 + 3 - 0) + 8 * 3) / 2^20 = 88 bytes.
// SAH (K_T 15, K_I 20): areas root 34, [0,4] 18, [0,2] 10, [2,4] 10, [4,8] 18:
//   15 (34 + 18) / 34 + 20 (10 + 10 + 18) / 34 = 1540 / 34.
TriangleSoup ThreeUnitTriangles() {
  TriangleSoup soup;
  soup.Add({0, 0, 0}, {1, 0, 1}, {0, 1, 1});
  soup.Add({3, 0, 0}, {4, 0, 1}, {3, 1, 1});
  soup.Add({7, 0, 0}, {8, 0, 1}, {7, 1, 1});
  return soup;
}

// The tree counted above.
absl::StatusOr<KdTree> HandCountedTree() {
  Config c = *Preset("median-16-2");
  c.max_leaf_size = 1;
  return BuildKdTree(ThreeUnitTriangles(), c);
}

TEST(Stats, HandCountedTree) {
  absl::StatusOr<KdTree> tree = HandCountedTree();
  ASSERT_TRUE(tree.ok());
  const TreeStats s = ComputeStats(*tree);
  EXPECT_EQ(s.inner, 2u);
  EXPECT_EQ(s.leaves, 3u);
  EXPECT_EQ(s.leaf_refs, 3u);
  EXPECT_EQ(s.empty_leaves, 0u);
  EXPECT_DOUBLE_EQ(s.avg_leaf_refs, 1.0);
  EXPECT_DOUBLE_EQ(s.empty_ratio, 0.0);
  EXPECT_EQ(s.max_depth, 2);
  EXPECT_DOUBLE_EQ(s.avg_depth, 5.0 / 3.0);
  EXPECT_DOUBLE_EQ(s.mem_report_mb, 88.0 / (1024 * 1024));
  EXPECT_NEAR(s.sah_cost, 1540.0 / 34.0, 1e-9);
  EXPECT_EQ(s.clipped, 0u);
  EXPECT_EQ(s.pruned, 0u);
  // 5 nodes * 8 + 3 leaves of one 4-wide packet (36 floats and 4 indices) *
  // 4 bytes: the whole tree (no lists, no vertices by index).
  EXPECT_EQ(s.tree_bytes, 5u * 8 + 3u * 40 * 4);
  EXPECT_EQ(tree->nodes[0].axis(), 0);
  EXPECT_FLOAT_EQ(tree->nodes[0].split, 4.0f);
  EXPECT_EQ(tree->nodes[0].index(), 4u);  // right child after the 3-node left subtree
}

TEST(Stats, EmptyLeavesHoldNoPacketAndAreCounted) {
  // Two triangles at both ends: median splits leave empty cells between them.
  TriangleSoup soup;
  soup.Add({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  soup.Add({15, 0, 0}, {16, 0, 0}, {15, 1, 0});
  soup.Add({15, 0, 0.5f}, {16, 0, 0.5f}, {15, 1, 0.5f});
  Config c = *Preset("median-16-2");
  c.max_leaf_size = 1;
  c.max_depth = 3;
  // Root [0,16] -> x 8: {T0} leaf | {T1,T2} -> x 12: empty | {T1,T2} -> x 14: empty | {T1,T2} (depth 3).
  const KdTree tree = *BuildKdTree(soup, c);
  const TreeStats s = ComputeStats(tree);
  EXPECT_EQ(s.leaves, 4u);
  EXPECT_EQ(s.empty_leaves, 2u);
  EXPECT_DOUBLE_EQ(s.empty_ratio, 0.5);
  EXPECT_EQ(s.leaf_refs, 3u);
  EXPECT_EQ(tree.leaf_soa.size(), 2u * kPacketFloats);  // {T0}, {T1, T2}
  int empty = 0;
  for (const KdNode& n : tree.nodes) empty += n.is_leaf() && n.index() == kEmptyLeaf;
  EXPECT_EQ(empty, 2);
  EXPECT_EQ(s.max_depth, 3);
}

// StatsToJson: every field, in the order the records have always had; counts
// as integers, non-finite values as null.
TEST(Stats, ToJsonFieldsInOrder) {
  absl::StatusOr<KdTree> tree = HandCountedTree();
  ASSERT_TRUE(tree.ok());
  TreeStats s = ComputeStats(*tree);
  const nlohmann::ordered_json j = StatsToJson(s);
  std::vector<std::string> keys;
  for (const auto& [key, value] : j.items()) keys.push_back(key);
  EXPECT_EQ(keys, (std::vector<std::string>{"N_I", "N_L", "N_empty", "N_TP", "N_AP", "R_E", "D_max",
                                            "D_avg", "N_CL", "N_PR", "N_lost_planar",
                                            "mem_report_mb", "tree_bytes", "build_peak_bytes",
                                            "sah_cost", "invalid_leaf_boxes"}));
  EXPECT_TRUE(j["N_I"].is_number_integer());
  EXPECT_EQ(j["N_I"].get<uint64_t>(), 2u);
  EXPECT_EQ(j["D_max"].get<int>(), 2);
  EXPECT_EQ(j["tree_bytes"].get<uint64_t>(), s.tree_bytes);
  EXPECT_DOUBLE_EQ(j["D_avg"].get<double>(), 5.0 / 3.0);
  EXPECT_DOUBLE_EQ(j["sah_cost"].get<double>(), s.sah_cost);
  EXPECT_EQ(j.dump().rfind("{\"N_I\":2,\"N_L\":3,\"N_empty\":0,\"N_TP\":3,\"N_AP\":1.0,", 0), 0u)
      << j.dump();
  s.avg_leaf_refs = std::nan("");
  s.avg_depth = INFINITY;
  const nlohmann::ordered_json bad = StatsToJson(s);
  EXPECT_NE(bad.dump().find("\"N_AP\":null,"), std::string::npos) << bad.dump();
  EXPECT_NE(bad.dump().find("\"D_avg\":null,"), std::string::npos) << bad.dump();
}

TEST(Stats, FingerprintNamesTheTree) {
  const TriangleSoup soup = ThreeUnitTriangles();
  Config c;
  c.use_binning = false;
  c.max_leaf_size = 1;
  absl::StatusOr<KdTree> a = BuildKdTree(soup, c);
  absl::StatusOr<KdTree> b = BuildKdTree(soup, c);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(TreeFingerprint(*a), TreeFingerprint(*b));  // same input, same tree
  c.max_leaf_size = 8;  // one leaf: another tree
  absl::StatusOr<KdTree> leaf = BuildKdTree(soup, c);
  ASSERT_TRUE(leaf.ok());
  EXPECT_NE(TreeFingerprint(*a), TreeFingerprint(*leaf));
  KdTree moved = *a;
  moved.nodes[0].split += 1.0f;  // one split position differs
  EXPECT_NE(TreeFingerprint(*a), TreeFingerprint(moved));
}

}  // namespace
}  // namespace kdtree
