// The build of the BVH over the kd-tree's leaves (leaf_bvh.h): one pass down
// the kd-tree with the cells splits each leaf into its groups (its flat
// groups and the rest), copies each group's triangles into packets of its
// own and bounds them clipped to the cell; the binary hierarchy of the kd
// nodes and the groups is then collapsed into nodes of up to eight children
// (wide_collapse.h).
#include "cc/kdtree/leaf_bvh.h"

#include <algorithm>
#include <cstdint>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "cc/base/memory_budget.h"
#include "cc/geometry/aabb.h"
#include "cc/kdtree/leaf_layout.h"
#include "cc/kdtree/wide_collapse.h"

namespace kdtree {
namespace {

// One triangle of a kd leaf: where it is in the tree's packets.
struct LaneRef {
  const float* packet;
  int lane;
  uint32_t id;
};

// The group key of `t`: the lowest axis (0, 1, 2) on which its three
// vertices share their coordinate, and that coordinate; (3, 0) when there is
// no such axis, which sorts after every plane.
std::pair<int, float> FlatKey(const LaneRef& t) {
  Vec3 v[3];
  PacketTriangle(t.packet, t.lane, &v[0], &v[1], &v[2]);
  for (int k = 0; k < 3; ++k) {
    if (v[0][k] == v[1][k] && v[1][k] == v[2][k]) return {k, v[0][k]};
  }
  return {3, 0.0f};
}

// The triangles of the kd leaf whose first packet is `first`, in packet order.
void LeafLanes(const KdTree& tree, uint32_t first, std::vector<LaneRef>* out) {
  ForEachPacketLane(tree.leaf_soa.data() + static_cast<size_t>(first) * kPacketFloats,
                    [out](const float* p, int l, uint32_t id) { out->push_back({p, l, id}); });
}

// A kd leaf's groups: per (axis, coordinate), the triangles flat on that
// plane, in the order of the keys, then the triangles flat on no axis; each
// group's triangles in the leaf's order.
class Grouper {
 public:
  // Calls f(const std::vector<LaneRef>&) on each group of the kd leaf whose
  // first packet is `first`.
  template <class F>
  void ForEachGroup(const KdTree& tree, uint32_t first, F f) {
    lanes_.clear();
    LeafLanes(tree, first, &lanes_);
    if (lanes_.empty()) return;
    keyed_.clear();
    for (size_t i = 0; i < lanes_.size(); ++i) {
      const std::pair<int, float> key = FlatKey(lanes_[i]);
      keyed_.push_back({key.first, key.second, i});
    }
    // A leaf of one key (most leaves of most scenes) is sorted already and
    // one group, in the leaf's order.
    if (std::get<0>(keyed_.front()) == std::get<0>(keyed_.back()) &&
        std::get<1>(keyed_.front()) == std::get<1>(keyed_.back()) &&
        std::is_sorted(keyed_.begin(), keyed_.end())) {
      f(lanes_);
      return;
    }
    std::sort(keyed_.begin(), keyed_.end());
    for (size_t i = 0; i < keyed_.size();) {
      group_.clear();
      size_t j = i;
      for (; j < keyed_.size() && std::get<0>(keyed_[j]) == std::get<0>(keyed_[i]) &&
             std::get<1>(keyed_[j]) == std::get<1>(keyed_[i]);
           ++j) {
        group_.push_back(lanes_[std::get<2>(keyed_[j])]);
      }
      f(group_);
      i = j;
    }
  }

 private:
  // The leaf's triangles, their keys (axis, coordinate, index in lanes_),
  // one group's triangles.
  std::vector<LaneRef> lanes_;
  std::vector<std::tuple<int, float, size_t>> keyed_;
  std::vector<LaneRef> group_;
};

class Builder {
 public:
  Builder(const KdTree& tree, LeafBvh* out) : tree_(tree), out_(out) {}

  // `packets`: LeafBvhPacketBytes(tree) in packets.
  void Build(uint64_t packets) {
    out_->leaves.bounds = tree_.bounds;
    out_->leaves.triangles = tree_.triangles;
    out_->leaves.config = tree_.config;
    // One allocation for the packets: as many as the groups need (fewer
    // when a group is dropped), written as the groups are made.
    out_->leaves.leaf_soa.resize(packets * kPacketFloats);  // every float written by Group
    const int64_t root = Node(0, tree_.bounds);
    out_->leaves.leaf_soa.resize(static_cast<size_t>(written_) * kPacketFloats);
    if (root >= 0) wide_collapse::Collapse(*this, static_cast<uint32_t>(root), out_);
  }

  // The binary hierarchy as wide_collapse::Collapse reads it.
  bool IsLeaf(uint32_t i) const { return v_[i].leaf; }
  const AABB& Box(uint32_t i) const { return v_[i].box; }
  void Children(uint32_t i, std::vector<uint32_t>* list) const {
    list->push_back(v_[i].kid[0]);
    list->push_back(v_[i].kid[1]);
  }
  uint32_t FirstPacket(uint32_t i) const { return v_[i].first; }
  uint32_t Packets(uint32_t i) const { return v_[i].packets; }

 private:
  struct V {
    AABB box;
    bool leaf = false;
    uint32_t first = 0, packets = 0;  // a leaf's packets in out_->leaves.leaf_soa
    uint32_t kid[2] = {0, 0};         // an inner node's children in v_
  };

  // A node over subtrees a and b (either may be -1: none); its index.
  int64_t Join(int64_t a, int64_t b) {
    if (a < 0) return b;
    if (b < 0) return a;
    V n;
    n.box = v_[a].box;
    n.box.Extend(v_[b].box);
    n.kid[0] = static_cast<uint32_t>(a);
    n.kid[1] = static_cast<uint32_t>(b);
    v_.push_back(n);
    return static_cast<int64_t>(v_.size() - 1);
  }

  // Kd node `index`, whose cell is `cell`: its subtree's index, -1 when it
  // holds no geometry.
  int64_t Node(uint32_t index, const AABB& cell) {
    const KdNode& n = tree_.nodes[index];
    if (n.is_leaf()) return n.index() == kEmptyLeaf ? -1 : Leaf(n.index(), cell);
    AABB left = cell, right = cell;
    left.hi[n.axis()] = n.split;
    right.lo[n.axis()] = n.split;
    const int64_t a = Node(index + 1, left);
    return Join(a, Node(n.index(), right));
  }

  // A kd leaf's groups (Grouper), each a BVH leaf, joined in their order.
  int64_t Leaf(uint32_t first, const AABB& cell) {
    int64_t node = -1;
    grouper_.ForEachGroup(tree_, first, [&](const std::vector<LaneRef>& group) {
      node = Join(node, Group(group, cell));
    });
    return node;
  }

  // `group` as a BVH leaf, its packets written after the last group's, its
  // box the union of its triangles' boxes clipped to `cell`; -1 when that is
  // empty (no triangle of the group meets the cell: none holds a hit there).
  int64_t Group(const std::vector<LaneRef>& group, const AABB& cell) {
    V g;
    g.leaf = true;
    for (const LaneRef& t : group) {
      Vec3 v[3];
      PacketTriangle(t.packet, t.lane, &v[0], &v[1], &v[2]);
      AABB b;
      for (const Vec3& x : v) b.Extend(x);
      b.lo = Max(b.lo, cell.lo);
      b.hi = Min(b.hi, cell.hi);
      if (b.Valid()) g.box.Extend(b);
    }
    if (!g.box.Valid()) return -1;
    g.first = written_;
    g.packets = static_cast<uint32_t>((group.size() + kPacketLanes - 1) / kPacketLanes);
    written_ += g.packets;
    // Each triangle's 9 floats (a, b, c) out of its packet's lane.
    rows_.clear();
    ids_.clear();
    for (const LaneRef& t : group) {
      for (int w = 0; w < 9; ++w) rows_.push_back(t.packet[w * kPacketLanes + t.lane]);
      ids_.push_back(t.id);
    }
    WriteLeafPacketsFromRows(rows_.data(), ids_.data(), group.size(),
                             out_->leaves.leaf_soa.data() + size_t{g.first} * kPacketFloats);
    v_.push_back(g);
    return static_cast<int64_t>(v_.size() - 1);
  }

  const KdTree& tree_;
  LeafBvh* out_;
  std::vector<V> v_;
  uint32_t written_ = 0;  // packets written
  std::vector<float> rows_;  // Group's scratch: its triangles' vertices
  std::vector<uint32_t> ids_;  // and indices
  Grouper grouper_;
};

}  // namespace

uint64_t LeafBvhPacketBytes(const KdTree& tree) {
  if (tree.nodes.empty() || !tree.bounds.Valid() || tree.leaf_soa.empty()) return 0;
  uint64_t packets = 0;
  Grouper grouper;
  for (const KdNode& n : tree.nodes) {
    if (!n.is_leaf() || n.index() == kEmptyLeaf) continue;
    grouper.ForEachGroup(tree, n.index(), [&](const std::vector<LaneRef>& group) {
      packets += (group.size() + kPacketLanes - 1) / kPacketLanes;
    });
  }
  return packets * kPacketFloats * sizeof(float);
}

absl::StatusOr<LeafBvh> BuildLeafBvh(const KdTree& tree, uint64_t max_packet_bytes,
                                     const std::string& how_to_raise) {
  LeafBvh bvh;
  if (tree.nodes.empty() || !tree.bounds.Valid() || tree.leaf_soa.empty()) return bvh;
  const uint64_t bytes = LeafBvhPacketBytes(tree);
  if (absl::Status st = CheckMemoryBudget(bytes, max_packet_bytes,
                                          "the BVH over the tree's leaves (its own leaf packets)",
                                          how_to_raise);
      !st.ok()) {
    return st;
  }
  const uint64_t packets = bytes / (kPacketFloats * sizeof(float));
  // A child slot holds kLeafBit | the first packet (2^31 packets are 320 GiB).
  if (packets >= LeafBvhNode::kLeafBit) {
    return absl::ResourceExhaustedError(absl::StrCat(
        "the BVH over the tree's leaves needs ", packets,
        " leaf packets, more than a node can address (2^31)"));
  }
  Builder(tree, &bvh).Build(packets);
  return bvh;
}

}  // namespace kdtree
