// The build of the BVH over the kd-tree's leaves (leaf_bvh.h): the boxes of
// every kd subtree's geometry in one pass down the tree with the cells, then
// the kd hierarchy collapsed into nodes of up to eight children
// (wide_collapse.h).
#include "cc/kdtree/leaf_bvh.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "cc/geometry/aabb.h"
#include "cc/kdtree/leaf_layout.h"
#include "cc/kdtree/wide_collapse.h"

namespace kdtree {
namespace {

class Builder {
 public:
  Builder(const KdTree& tree, LeafBvh* out)
      : tree_(tree), out_(out), box_(tree.nodes.size()) {}

  void Build() {
    if (Bound(0, tree_.bounds).Valid()) wide_collapse::Collapse(*this, 0, out_);
  }

  // The hierarchy as wide_collapse::Collapse reads it (kd node indices).
  bool IsLeaf(uint32_t index) const { return tree_.nodes[index].is_leaf(); }
  const AABB& Box(uint32_t index) const { return box_[index]; }
  // The children of kd node `index` that hold geometry.
  void Children(uint32_t index, std::vector<uint32_t>* list) const {
    const uint32_t left = index + 1, right = tree_.nodes[index].index();
    if (box_[left].Valid()) list->push_back(left);
    if (box_[right].Valid()) list->push_back(right);
  }
  uint32_t FirstPacket(uint32_t index) const { return tree_.nodes[index].index(); }
  // The number of packets of the leaf at `index`.
  uint32_t Packets(uint32_t index) const {
    uint32_t count = 1;
    const float* p = tree_.leaf_soa.data() + static_cast<size_t>(FirstPacket(index)) * kPacketFloats;
    for (;; p += kPacketFloats, ++count) {
      uint32_t id0;
      std::memcpy(&id0, p + kPacketIds, sizeof(id0));
      if (id0 & kLastPacket) return count;
    }
  }

 private:
  // The box of the triangles under kd node `index` whose cell is `cell`,
  // each triangle's box clipped to its leaf's cell; empty when there are
  // none. Kept in box_.
  AABB Bound(uint32_t index, const AABB& cell) {
    const KdNode& n = tree_.nodes[index];
    AABB b;
    if (n.is_leaf()) {
      if (n.index() != kEmptyLeaf) b = LeafBox(n.index(), cell);
    } else {
      AABB left = cell, right = cell;
      left.hi[n.axis()] = n.split;
      right.lo[n.axis()] = n.split;
      b = Bound(index + 1, left);
      b.Extend(Bound(n.index(), right));
    }
    box_[index] = b;
    return b;
  }

  AABB LeafBox(uint32_t first_packet, const AABB& cell) const {
    AABB b;
    const float* p = tree_.leaf_soa.data() + static_cast<size_t>(first_packet) * kPacketFloats;
    for (;; p += kPacketFloats) {
      uint32_t ids[kPacketLanes];
      std::memcpy(ids, p + kPacketIds, sizeof(ids));
      for (int l = 0; l < kPacketLanes; ++l) {
        if (ids[l] == kPadLane) continue;
        Vec3 v[3];
        PacketTriangle(p, l, &v[0], &v[1], &v[2]);
        AABB t;
        for (const Vec3& x : v) t.Extend(x);
        t.lo = Max(t.lo, cell.lo);
        t.hi = Min(t.hi, cell.hi);
        if (t.Valid()) b.Extend(t);
      }
      if (ids[0] & kLastPacket) return b;
    }
  }

  const KdTree& tree_;
  LeafBvh* out_;
  std::vector<AABB> box_;  // per kd node
};

}  // namespace

LeafBvh BuildLeafBvh(const KdTree& tree) {
  LeafBvh bvh;
  if (tree.nodes.empty() || !tree.bounds.Valid() || tree.leaf_soa.empty()) return bvh;
  Builder(tree, &bvh).Build();
  return bvh;
}

}  // namespace kdtree
