// Statistics of a built tree: the report's tables 5-10 (N_I, N_L, N_TP, N_AP,
// mem, R_E, D_max, D_avg, N_CL, N_PR) and the tree's SAH cost.
#ifndef KDTREE_CC_KDTREE_STATS_H_
#define KDTREE_CC_KDTREE_STATS_H_

#include <cstdint>
#include <string>

#include "cc/kdtree/tree.h"
#include "nlohmann/json.hpp"

namespace kdtree {

// SAH cost constants (Wald & Havran, "On building fast kd-trees for ray
// tracing, and on doing that in O(N log N)", IEEE RT 2006): traversal step
// K_T = 15, triangle test K_I = 20. The tree's cost is
//   sum over inner nodes K_T SA(n) / SA(root) + sum over leaves K_I N(l) SA(l) / SA(root).
inline constexpr double kSahTraversalCost = 15.0;
inline constexpr double kSahIntersectionCost = 20.0;

struct TreeStats {
  uint64_t inner = 0;         // N_I
  uint64_t leaves = 0;        // N_L
  uint64_t empty_leaves = 0;
  uint64_t leaf_refs = 0;     // N_TP: references summed over leaves
  double avg_leaf_refs = 0;   // N_AP = N_TP / N_L
  double empty_ratio = 0;     // R_E = empty leaves / N_L
  int max_depth = 0;          // D_max over leaves (root depth 0)
  double avg_depth = 0;       // D_avg over leaves
  uint64_t clipped = 0;       // N_CL
  uint64_t pruned = 0;        // N_PR
  uint64_t lost_planar = 0;   // seed mode: in-plane references lost
  // mem as the report computes it (MB of 2^20 bytes; fits every row 18 entry):
  // [8 (N_I + N_L) + 4 (N_TP + N_L - N_empty) + 8 N_tri] / 2^20.
  double mem_report_mb = 0;
  // Bytes of the traversable tree: its nodes and leaf packets (tree.h), all
  // a traversal reads.
  uint64_t tree_bytes = 0;
  // Peak bytes of build references (clipped boxes included) during the build,
  // with the box array of an index build (build_ref.h).
  uint64_t build_peak_bytes = 0;
  double sah_cost = 0;
  // Leaves that are not valid boxes (must be 0) and triangles absent from
  // every leaf (neither pruned as non-overlapping nor lost: must be 0).
  uint64_t invalid_leaf_boxes = 0;
};

TreeStats ComputeStats(const KdTree& tree);

// One JSON object with every field of TreeStats plus the build counters:
// N_I, N_L, N_empty, N_TP, N_AP, R_E, D_max, D_avg, N_CL, N_PR, N_lost_planar,
// mem_report_mb, tree_bytes, build_peak_bytes, sah_cost, invalid_leaf_boxes,
// in this order (kdrt's and build_bench's records).
nlohmann::ordered_json StatsToJson(const TreeStats& s);

// FNV-1a (64 bits, over 64-bit words) of the tree: nodes (split bits and index
// bits), leaf packets (vertices and triangle indices) and build counters. Two
// builds have the same fingerprint when they wrote the same tree; benchmarks
// use it to check that a faster builder still writes the tree it wrote
// before. (Before 4c5d23d the tree also held the report's reference lists and
// a second node array, which the fingerprint hashed: fingerprints recorded
// before it are not comparable with later ones.)
uint64_t TreeFingerprint(const KdTree& tree);

}  // namespace kdtree

#endif  // KDTREE_CC_KDTREE_STATS_H_
