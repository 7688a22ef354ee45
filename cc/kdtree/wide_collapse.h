// A binary hierarchy with boxes collapsed into the eight-wide nodes that the
// leaf-BVH traversals read (leaf_bvh.h): a node's slots start as its one
// subtree, and the inner slot with the largest surface area is replaced by
// its children until eight slots are filled or only leaves remain (Wald,
// Benthin & Boulos, "Getting rid of packets", RT 2008; Wald et al., "Embree",
// ACM TOG 33(4), 2014). Used by the BVH over the kd-tree's leaves
// (leaf_bvh.cc) and by the BVH over whole triangles (triangle_bvh.cc).
#ifndef KDTREE_CC_KDTREE_WIDE_COLLAPSE_H_
#define KDTREE_CC_KDTREE_WIDE_COLLAPSE_H_

#include <algorithm>
#include <cstdint>
#include <vector>

#include "cc/geometry/aabb.h"
#include "cc/kdtree/leaf_bvh.h"

namespace kdtree {
namespace wide_collapse {

inline float HalfArea(const AABB& b) {
  const Vec3 e = b.Extent();
  return e.x * e.y + e.y * e.z + e.z * e.x;
}

// Writes the node for subtree `index` of `h` (not empty) and those below it
// into out->nodes; returns its index. H provides, for a subtree index i:
//   bool IsLeaf(i); const AABB& Box(i) (valid);
//   void Children(i, std::vector<uint32_t>*) (inner: its one or two
//     non-empty children, appended);
//   uint32_t FirstPacket(i), uint32_t Packets(i) (leaf: its first packet in
//     the leaf packets the traversal reads, and their number).
// A leaf at `index` makes a node of one slot.
template <class H>
uint32_t Collapse(const H& h, uint32_t index, LeafBvh* out) {
  std::vector<uint32_t> slots{index};
  std::vector<uint32_t> kids;
  while (slots.size() < static_cast<size_t>(kBvhWidth)) {
    int widest = -1;
    for (size_t j = 0; j < slots.size(); ++j) {
      if (h.IsLeaf(slots[j])) continue;
      if (widest < 0 || HalfArea(h.Box(slots[j])) > HalfArea(h.Box(slots[widest]))) {
        widest = static_cast<int>(j);
      }
    }
    if (widest < 0) break;
    kids.clear();
    h.Children(slots[widest], &kids);
    slots[widest] = kids[0];
    if (kids.size() > 1) slots.push_back(kids[1]);
  }
  const uint32_t me = static_cast<uint32_t>(out->nodes.size());
  out->nodes.emplace_back();
  // (out->nodes grows below: the node is indexed, not held.)
  const auto set_slot = [out, me](int s, uint32_t child, const AABB& b, uint32_t packets) {
    LeafBvhNode& node = out->nodes[me];
    node.child[s] = child;
    node.packets[s] = static_cast<uint8_t>(std::min(packets, 255u));
    for (int k = 0; k < 3; ++k) {
      node.box[k][s] = b.lo[k];
      node.box[3 + k][s] = b.hi[k];
    }
  };
  for (int s = 0; s < kBvhWidth; ++s) set_slot(s, LeafBvhNode::kNone, AABB(), 0);
  for (size_t s = 0; s < slots.size(); ++s) {
    const uint32_t i = slots[s];
    if (h.IsLeaf(i)) {
      set_slot(static_cast<int>(s), LeafBvhNode::kLeafBit | h.FirstPacket(i), h.Box(i),
               h.Packets(i));
    } else {
      const uint32_t child = Collapse(h, i, out);
      set_slot(static_cast<int>(s), child, h.Box(i), 0);
    }
  }
  return me;
}

}  // namespace wide_collapse
}  // namespace kdtree

#endif  // KDTREE_CC_KDTREE_WIDE_COLLAPSE_H_
