// The build of the BVH over the kd-tree's leaves (leaf_bvh.h): the boxes of
// every kd subtree's geometry in one pass down the tree with the cells, then
// the kd hierarchy collapsed into nodes of up to eight children.
#include "cc/kdtree/leaf_bvh.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "cc/geometry/aabb.h"
#include "cc/kdtree/leaf_layout.h"

namespace kdtree {
namespace {

class Builder {
 public:
  Builder(const KdTree& tree, LeafBvh* out)
      : tree_(tree), out_(out), box_(tree.nodes.size()) {}

  void Build() {
    if (Bound(0, tree_.bounds).Valid()) Emit(0);
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

  static float HalfArea(const AABB& b) {
    const Vec3 e = b.Extent();
    return e.x * e.y + e.y * e.z + e.z * e.x;
  }

  // The children of kd node `index` that hold geometry.
  void AddChildren(uint32_t index, std::vector<uint32_t>* list) const {
    const uint32_t left = index + 1, right = tree_.nodes[index].index();
    if (box_[left].Valid()) list->push_back(left);
    if (box_[right].Valid()) list->push_back(right);
  }

  // The node for the kd subtree at `index` (not empty): its children
  // expanded, the largest inner one by surface area first, to at most
  // kBvhWidth subtrees; a leaf at `index` makes a node of one slot.
  uint32_t Emit(uint32_t index) {
    std::vector<uint32_t> slots{index};
    while (slots.size() < static_cast<size_t>(kBvhWidth)) {
      int widest = -1;
      for (size_t j = 0; j < slots.size(); ++j) {
        if (tree_.nodes[slots[j]].is_leaf()) continue;
        if (widest < 0 || HalfArea(box_[slots[j]]) > HalfArea(box_[slots[widest]])) {
          widest = static_cast<int>(j);
        }
      }
      if (widest < 0) break;
      std::vector<uint32_t> kids;
      AddChildren(slots[widest], &kids);
      slots[widest] = kids[0];
      if (kids.size() > 1) slots.push_back(kids[1]);
    }
    const uint32_t me = static_cast<uint32_t>(out_->nodes.size());
    out_->nodes.emplace_back();
    for (int s = 0; s < kBvhWidth; ++s) SetSlot(me, s, LeafBvhNode::kNone, AABB());
    for (size_t s = 0; s < slots.size(); ++s) {
      const KdNode& n = tree_.nodes[slots[s]];
      const uint32_t child = n.is_leaf() ? (LeafBvhNode::kLeafBit | n.index()) : Emit(slots[s]);
      SetSlot(me, static_cast<int>(s), child, box_[slots[s]]);
      if (n.is_leaf()) {
        out_->nodes[me].packets[s] = static_cast<uint8_t>(std::min(PacketCount(n.index()), 255u));
      }
    }
    return me;
  }

  // The number of packets of the leaf whose first packet is `first`.
  uint32_t PacketCount(uint32_t first) const {
    uint32_t count = 1;
    for (const float* p = tree_.leaf_soa.data() + static_cast<size_t>(first) * kPacketFloats;;
         p += kPacketFloats, ++count) {
      uint32_t id0;
      std::memcpy(&id0, p + kPacketIds, sizeof(id0));
      if (id0 & kLastPacket) return count;
    }
  }

  // (out_->nodes may have grown since `me` was made: indexed, not held.)
  void SetSlot(uint32_t me, int s, uint32_t child, const AABB& b) {
    LeafBvhNode& node = out_->nodes[me];
    node.child[s] = child;
    node.packets[s] = 0;
    for (int k = 0; k < 3; ++k) {
      node.box[k][s] = b.lo[k];
      node.box[3 + k][s] = b.hi[k];
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
