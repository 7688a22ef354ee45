// The build of the BVH over whole triangles (triangle_bvh.h).
#include "cc/kdtree/triangle_bvh.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "cc/kdtree/builder.h"
#include "cc/kdtree/leaf_layout.h"
#include "cc/kdtree/wide_collapse.h"

namespace kdtree {
namespace {

// Binary nodes deeper than this split at the median, which halves them, and
// none goes past kMaxDepth: the eight-wide traversal's stack holds 7 entries
// a level for up to kMaxTraversalStack levels.
constexpr int kMedianDepth = 36;
constexpr int kMaxDepth = 60;

struct Node {
  AABB box;
  uint32_t left = 0, right = 0;  // inner: children
  uint32_t begin = 0, count = 0;  // its triangles: order_index_[begin, begin + count)
  uint32_t first_packet = 0;
  bool leaf = false;
};

uint32_t PacketsOf(uint32_t count) { return (count + kPacketLanes - 1) / kPacketLanes; }

class Builder {
 public:
  Builder(const TriangleSoup& soup, const TriangleBvhOptions& options, LeafBvh* out)
      : soup_(soup), options_(options), out_(out) {}

  void Build() {
    out_->leaves.triangles = soup_.size();
    for (uint32_t i = 0; i < soup_.size(); ++i) {
      const AABB b = soup_.Bounds(i);
      order_.push_back(i);
      boxes_.push_back(b);
      centroids_.push_back((b.lo + b.hi) * 0.5f);
    }
    if (order_.empty()) return;
    Split();
    out_->leaves.bounds = nodes_[0].box;
    WritePackets();
    wide_collapse::Collapse(*this, 0, out_);
  }

  // The hierarchy as wide_collapse::Collapse reads it.
  bool IsLeaf(uint32_t i) const { return nodes_[i].leaf; }
  const AABB& Box(uint32_t i) const { return nodes_[i].box; }
  void Children(uint32_t i, std::vector<uint32_t>* kids) const {
    kids->push_back(nodes_[i].left);
    kids->push_back(nodes_[i].right);
  }
  uint32_t FirstPacket(uint32_t i) const { return nodes_[i].first_packet; }
  uint32_t Packets(uint32_t i) const { return PacketsOf(nodes_[i].count); }

 private:
  // The binary hierarchy, top down with a stack of (node, depth).
  void Split() {
    order_index_.resize(order_.size());
    for (uint32_t j = 0; j < order_index_.size(); ++j) order_index_[j] = j;
    nodes_.emplace_back();
    nodes_[0].count = static_cast<uint32_t>(order_.size());
    std::vector<std::pair<uint32_t, int>> stack{{0, 0}};
    while (!stack.empty()) {
      const auto [me, depth] = stack.back();
      stack.pop_back();
      const uint32_t begin = nodes_[me].begin, count = nodes_[me].count;
      AABB box, centroids;
      for (uint32_t j = begin; j < begin + count; ++j) {
        box.Extend(boxes_[order_index_[j]]);
        centroids.Extend(centroids_[order_index_[j]]);
      }
      nodes_[me].box = box;
      const uint32_t mid = Partition(box, centroids, begin, count, depth);
      if (mid == begin) {
        nodes_[me].leaf = true;
        continue;
      }
      const uint32_t left = static_cast<uint32_t>(nodes_.size());
      nodes_.resize(nodes_.size() + 2);
      nodes_[left].begin = begin;
      nodes_[left].count = mid - begin;
      nodes_[left + 1].begin = mid;
      nodes_[left + 1].count = begin + count - mid;
      nodes_[me].left = left;
      nodes_[me].right = left + 1;
      stack.push_back({left + 1, depth + 1});
      stack.push_back({left, depth + 1});
    }
  }

  // Where node [begin, begin + count) splits (its triangles reordered), or
  // `begin` for a leaf.
  uint32_t Partition(const AABB& box, const AABB& centroids, uint32_t begin, uint32_t count,
                     int depth) {
    if (count <= static_cast<uint32_t>(kPacketLanes) || depth >= kMaxDepth) return begin;
    int axis = -1, bin = -1;
    float cost = INFINITY;
    if (depth < kMedianDepth) BestSplit(centroids, begin, count, &axis, &bin, &cost);
    if (count <= static_cast<uint32_t>(options_.max_leaf)) {
      const float leaf = HalfArea(box) * static_cast<float>(PacketsOf(count));
      if (axis < 0 || leaf <= options_.traversal_cost * HalfArea(box) + cost) return begin;
    }
    uint32_t* first = order_index_.data() + begin;
    uint32_t* last = first + count;
    uint32_t* mid = first;
    if (axis >= 0) {
      mid = std::partition(first, last, [&](uint32_t t) { return Bin(centroids, axis, t) <= bin; });
    }
    if (mid == first || mid == last) {  // no SAH split, or it left a side empty: the median
      const int k = centroids.LongestAxis();
      mid = first + count / 2;
      std::nth_element(first, mid, last, [&](uint32_t a, uint32_t b) {
        return centroids_[a][k] < centroids_[b][k];
      });
    }
    return begin + static_cast<uint32_t>(mid - first);
  }

  // In double: the extent of finite floats may overflow a float.
  int Bin(const AABB& centroids, int axis, uint32_t t) const {
    const double lo = centroids.lo[axis], extent = centroids.hi[axis] - lo;
    const int b = static_cast<int>((centroids_[t][axis] - lo) / extent * options_.bins);
    return std::min(std::max(b, 0), options_.bins - 1);
  }

  // The binned SAH's best plane: *axis, the last bin on its left, and its
  // cost (the children's half areas times their leaf packets); *axis stays
  // -1 when every centroid coincides.
  void BestSplit(const AABB& centroids, uint32_t begin, uint32_t count, int* axis, int* bin,
                 float* cost) const {
    const int bins = options_.bins;
    std::vector<AABB> box(bins), right_box(bins);
    std::vector<uint32_t> n(bins), right_n(bins);
    for (int k = 0; k < 3; ++k) {
      if (!(centroids.hi[k] > centroids.lo[k])) continue;
      std::fill(box.begin(), box.end(), AABB());
      std::fill(n.begin(), n.end(), 0u);
      for (uint32_t j = begin; j < begin + count; ++j) {
        const int b = Bin(centroids, k, order_index_[j]);
        box[b].Extend(boxes_[order_index_[j]]);
        ++n[b];
      }
      AABB acc;
      uint32_t c = 0;
      for (int b = bins - 1; b > 0; --b) {
        acc.Extend(box[b]);
        c += n[b];
        right_box[b] = acc;
        right_n[b] = c;
      }
      acc = AABB();
      c = 0;
      for (int b = 0; b + 1 < bins; ++b) {
        acc.Extend(box[b]);
        c += n[b];
        if (c == 0 || right_n[b + 1] == 0) continue;
        const float s = HalfArea(acc) * static_cast<float>(PacketsOf(c)) +
                        HalfArea(right_box[b + 1]) * static_cast<float>(PacketsOf(right_n[b + 1]));
        if (s < *cost) {
          *cost = s;
          *axis = k;
          *bin = b;
        }
      }
    }
  }

  static float HalfArea(const AABB& b) { return wide_collapse::HalfArea(b); }

  // Each leaf's triangles in packets of four (leaf_layout.h), leaves in
  // node order.
  void WritePackets() {
    uint32_t packets = 0;
    for (Node& n : nodes_) {
      if (!n.leaf) continue;
      n.first_packet = packets;
      packets += PacketsOf(n.count);
    }
    out_->leaves.leaf_soa.assign(static_cast<size_t>(packets) * kPacketFloats, 0.0f);
    std::vector<uint32_t> ids;
    for (const Node& n : nodes_) {
      if (!n.leaf) continue;
      ids.clear();
      for (uint32_t k = 0; k < n.count; ++k) ids.push_back(order_[order_index_[n.begin + k]]);
      WriteLeafPackets(soup_.v.data(), ids.data(), ids.size(),
                       out_->leaves.leaf_soa.data() +
                           static_cast<size_t>(n.first_packet) * kPacketFloats);
    }
  }

  const TriangleSoup& soup_;
  const TriangleBvhOptions options_;
  LeafBvh* out_;
  std::vector<uint32_t> order_;        // the soup's triangles (all kept)
  std::vector<AABB> boxes_;            // per triangle
  std::vector<Vec3> centroids_;        // per triangle: its box's centre
  std::vector<uint32_t> order_index_;  // triangles, in leaf order
  std::vector<Node> nodes_;            // nodes_[0]: the root
};

}  // namespace

absl::StatusOr<LeafBvh> BuildTriangleBvh(const TriangleSoup& soup,
                                         const TriangleBvhOptions& options) {
  if (absl::Status s = CheckBuildInput(soup); !s.ok()) return s;
  LeafBvh bvh;
  Builder(soup, options, &bvh).Build();
  return bvh;
}

}  // namespace kdtree
