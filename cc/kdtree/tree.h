// The kd-tree as plain data: builders produce it, traversal reads it.
//
// Layout of the report (section "Spatial median kd-tree"): every node is 8
// bytes. The two low bits of `bits` hold the split axis (0, 1, 2) or the leaf
// flag (3). An inner node stores the split position in `split`; its left child
// is the next node in the array and `bits >> 2` is the index of its right
// child. A leaf's `bits >> 2` points into `refs` at a count followed by that
// many triangle indices (a count-prefixed list). All empty leaves share the
// single count 0 stored at refs[0].
#ifndef KDTREE_CC_KDTREE_TREE_H_
#define KDTREE_CC_KDTREE_TREE_H_

#include <cstdint>
#include <vector>

#include "cc/base/huge_pages.h"
#include "cc/geometry/aabb.h"
#include "cc/geometry/intersect.h"
#include "cc/kdtree/config.h"

namespace kdtree {

struct KdNode {
  static constexpr uint32_t kLeaf = 3;
  static constexpr uint32_t kMaxIndex = (1u << 30) - 1;

  float split;    // inner nodes: split position
  uint32_t bits;  // (index << 2) | axis-or-leaf

  bool is_leaf() const { return (bits & 3u) == kLeaf; }
  int axis() const { return static_cast<int>(bits & 3u); }
  // Inner node: index of the right child. Leaf: offset of its list in refs.
  uint32_t index() const { return bits >> 2; }

  static KdNode Inner(int axis, float split, uint32_t right) {
    return KdNode{split, (right << 2) | static_cast<uint32_t>(axis)};
  }
  static KdNode Leaf(uint32_t refs_offset) { return KdNode{0.0f, (refs_offset << 2) | kLeaf}; }
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
  AABB bounds;                  // root box: union of the triangles' tight boxes
  HugeBuffer<KdNode> nodes;      // nodes[0] is the root
  HugeBuffer<uint32_t> refs;     // count-prefixed leaf lists; refs[0] == 0
  // The triangles' vertices, 3 per triangle (a, b, c as in the soup), by
  // index: the one copy of each triangle outside the leaf layout. The
  // watertight test (cc/geometry/watertight.h) needs the exact shared
  // vertices; the fast test forms its edges (TriAccel: v0, e1 = b - a,
  // e2 = c - a) at each test, from these or from the leaf packets, the same
  // floats a stored copy would hold.
  HugeBuffer<Vec3> verts;
  // Optional, leaf order (cc/kdtree/leaf_layout.h): each leaf's triangle
  // vertices and indices in packets of 4 triangles (structure of arrays, 40
  // words per packet) in leaf_soa; leaf_nodes is `nodes` with each leaf
  // pointing at its first packet. Empty: traversal reads `verts` by index.
  HugeBuffer<float> leaf_soa;
  HugeBuffer<KdNode> leaf_nodes;
  BuildCounters counters;
  double build_seconds = 0;     // T_B: triangles in memory to traversable tree

  size_t num_triangles() const { return verts.size() / 3; }
  const uint32_t* LeafBegin(const KdNode& leaf) const { return &refs[leaf.index() + 1]; }
  uint32_t LeafCount(const KdNode& leaf) const { return refs[leaf.index()]; }
};

}  // namespace kdtree

#endif  // KDTREE_CC_KDTREE_TREE_H_
