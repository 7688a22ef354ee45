// The kd-tree as plain data: builders produce it, traversal reads it.
//
// Nodes as in the report (section "Spatial median kd-tree"): every node is 8
// bytes. The two low bits of `bits` hold the split axis (0, 1, 2) or the leaf
// flag (3). An inner node stores the split position in `split`; its left child
// is the next node in the array and `bits >> 2` is the index of its right
// child. The report's leaf points at a count-prefixed list of triangle
// indices; the builders produce that form (ListTree, list_tree.h), and the
// finished tree's leaf points at its triangles themselves, stored in leaf
// order in packets of four (leaf_layout.h): all the traversal reads, with no
// copy of the triangles beside them (a triangle is stored once per leaf that
// references it).
#ifndef KDTREE_CC_KDTREE_TREE_H_
#define KDTREE_CC_KDTREE_TREE_H_

#include <cstddef>
#include <cstdint>

#include "cc/base/huge_pages.h"
#include "cc/geometry/aabb.h"
#include "cc/kdtree/config.h"

namespace kdtree {

struct KdNode {
  static constexpr uint32_t kLeaf = 3;
  static constexpr uint32_t kMaxIndex = (1u << 30) - 1;

  float split;    // inner nodes: split position
  uint32_t bits;  // (index << 2) | axis-or-leaf

  bool is_leaf() const { return (bits & 3u) == kLeaf; }
  int axis() const { return static_cast<int>(bits & 3u); }
  // Inner node: index of the right child. Leaf: offset of its list in
  // ListTree::refs, or of its first packet in KdTree::leaf_soa.
  uint32_t index() const { return bits >> 2; }

  static KdNode Inner(int axis, float split, uint32_t right) {
    return KdNode{split, (right << 2) | static_cast<uint32_t>(axis)};
  }
  static KdNode Leaf(uint32_t offset) { return KdNode{0.0f, (offset << 2) | kLeaf}; }
};
static_assert(sizeof(KdNode) == 8, "the report's node is 8 bytes");

// Counters gathered while building (the report's N_CL, N_PR) and the
// references lost by the seed-compatible strict partition.
struct BuildCounters {
  uint64_t clipped = 0;        // N_CL: clip operations (one reference became two)
  uint64_t pruned_box = 0;     // clipped boxes outside their child, dropped
  uint64_t pruned_leaf = 0;    // triangles whose surface misses the leaf box
  uint64_t lost_planar = 0;    // seed mode only: in-plane references sent nowhere
  // Largest number of build-reference slots in use at once: the references
  // and the slots a partition leaves between its two sides (builder.cc).
  uint64_t peak_build_refs = 0;
  // The bytes they held (BuildRef or IndexRef slots, plus the box array an
  // IndexRef build reads: build_ref.h).
  uint64_t peak_build_bytes = 0;
  uint64_t pruned() const { return pruned_box + pruned_leaf; }  // N_PR
};

// The arrays are HugeBuffers (cc/base/huge_pages.h): on huge pages when large,
// and resize() leaves new elements unwritten (the builders fill them, in
// parallel where they can).
struct KdTree {
  Config config;
  AABB bounds;               // root box: union of the triangles' tight boxes
  // nodes[0] is the root. A leaf's index() is its first packet in leaf_soa,
  // or kEmptyLeaf (leaf_layout.h) for an empty leaf.
  HugeBuffer<KdNode> nodes;
  // Each leaf's triangles, in packets of 4 (structure of arrays, 40 words a
  // packet: the vertices exactly as in the soup, which the watertight test
  // needs, then the triangle indices; leaf_layout.h). A triangle in several
  // leaves is stored in each: no vertex is read by index.
  HugeBuffer<float> leaf_soa;
  size_t triangles = 0;      // the soup's triangle count
  BuildCounters counters;
  double build_seconds = 0;  // T_B: triangles in memory to traversable tree

  size_t num_triangles() const { return triangles; }
};

}  // namespace kdtree

#endif  // KDTREE_CC_KDTREE_TREE_H_
