#include "cc/kdtree/stats.h"

#include <cstring>
#include <vector>

#include "cc/base/fnv.h"
#include "cc/kdtree/build_ref.h"
#include "cc/kdtree/leaf_layout.h"
#include "nlohmann/json.hpp"

namespace kdtree {
namespace {

struct Walker {
  const KdTree& tree;
  TreeStats* s;
  double root_area;
  uint64_t depth_sum = 0;

  void Walk(uint32_t index, const AABB& box, int depth) {
    const KdNode& node = tree.nodes[index];
    const double rel = root_area > 0 ? box.SurfaceArea() / root_area : 0.0;
    if (node.is_leaf()) {
      const uint32_t count = LeafTriangleCount(tree, node);
      ++s->leaves;
      if (count == 0) ++s->empty_leaves;
      s->leaf_refs += count;
      depth_sum += depth;
      if (depth > s->max_depth) s->max_depth = depth;
      if (!box.Valid()) ++s->invalid_leaf_boxes;
      s->sah_cost += kSahIntersectionCost * count * rel;
      return;
    }
    ++s->inner;
    s->sah_cost += kSahTraversalCost * rel;
    Walk(index + 1, box.LeftOf(node.axis(), node.split), depth + 1);
    Walk(node.index(), box.RightOf(node.axis(), node.split), depth + 1);
  }
};

}  // namespace

TreeStats ComputeStats(const KdTree& tree) {
  TreeStats s;
  if (tree.nodes.empty()) return s;
  Walker w{tree, &s, tree.bounds.Valid() ? tree.bounds.SurfaceArea() : 0.0};
  w.Walk(0, tree.bounds, 0);
  s.avg_leaf_refs = s.leaves ? static_cast<double>(s.leaf_refs) / s.leaves : 0.0;
  s.empty_ratio = s.leaves ? static_cast<double>(s.empty_leaves) / s.leaves : 0.0;
  s.avg_depth = s.leaves ? static_cast<double>(w.depth_sum) / s.leaves : 0.0;
  s.clipped = tree.counters.clipped;
  s.pruned = tree.counters.pruned();
  s.lost_planar = tree.counters.lost_planar;
  s.mem_report_mb = (8.0 * (s.inner + s.leaves) + 4.0 * (s.leaf_refs + s.leaves - s.empty_leaves) +
                     8.0 * tree.num_triangles()) /
                    (1024.0 * 1024.0);
  s.tree_bytes = TreeBytes(tree);
  s.build_peak_bytes = tree.counters.peak_build_bytes;
  return s;
}

namespace {
// FNV-1a over 64-bit words, the tail byte by byte (cc/base/fnv.h), from the
// offset basis as the fingerprint was first written: 1469598103934665603, the
// FNV basis 14695981039346656037 with its last digit lost. Kept, so that
// fingerprints stay comparable with every recorded result and note.
constexpr uint64_t kFingerprintOffset = 1469598103934665603ull;
struct Fnv1a {
  uint64_t h = kFingerprintOffset;
  void Add(const void* data, size_t bytes) { h = FnvWords(data, bytes, h, FnvTail::kBytes); }
};
}  // namespace

uint64_t TreeFingerprint(const KdTree& tree) {
  Fnv1a f;
  f.Add(tree.nodes.data(), tree.nodes.size() * sizeof(KdNode));
  f.Add(tree.leaf_soa.data(), tree.leaf_soa.size() * sizeof(float));
  const uint64_t counters[] = {tree.counters.clipped, tree.counters.pruned_box,
                               tree.counters.pruned_leaf, tree.counters.lost_planar};
  f.Add(counters, sizeof(counters));
  return f.h;
}

nlohmann::ordered_json StatsToJson(const TreeStats& s) {
  return {{"N_I", s.inner},
          {"N_L", s.leaves},
          {"N_empty", s.empty_leaves},
          {"N_TP", s.leaf_refs},
          {"N_AP", s.avg_leaf_refs},
          {"R_E", s.empty_ratio},
          {"D_max", s.max_depth},
          {"D_avg", s.avg_depth},
          {"N_CL", s.clipped},
          {"N_PR", s.pruned},
          {"N_lost_planar", s.lost_planar},
          {"mem_report_mb", s.mem_report_mb},
          {"tree_bytes", s.tree_bytes},
          {"build_peak_bytes", s.build_peak_bytes},
          {"sah_cost", s.sah_cost},
          {"invalid_leaf_boxes", s.invalid_leaf_boxes}};
}

}  // namespace kdtree
