// The running size of one kd-tree build against BuildLimits::max_bytes
// (builder.h), shared by every builder of the tree: the fragments built in
// parallel (parallel_build.h) and the local subtrees (builder.cc). Each node
// and leaf is counted at the size it has when the build holds the most: while
// the leaves are laid out, both the lists (list_tree.h) and the finished tree
// (leaf_layout.h) exist, so a node counts twice and a leaf its list (count + 1
// words) and its packets of four triangles.
#ifndef KDTREE_CC_KDTREE_BUILD_BUDGET_H_
#define KDTREE_CC_KDTREE_BUILD_BUDGET_H_

#include <atomic>
#include <cstddef>
#include <cstdint>

#include "cc/kdtree/leaf_layout.h"
#include "cc/kdtree/tree.h"

namespace kdtree {

class BuildBudget {
 public:
  static constexpr uint64_t kNodeBytes = 2 * sizeof(KdNode);
  static constexpr uint64_t kPacketBytes = kPacketFloats * sizeof(float);

  explicit BuildBudget(uint64_t max_bytes) : max_bytes_(max_bytes) {}

  // Count a node, or a leaf of `refs` triangles; false once the build is over
  // its budget (then it stays over).
  bool AddNode() { return Add(kNodeBytes); }
  bool AddLeaf(size_t refs) {
    return Add(sizeof(uint32_t) * (refs + 1) + kPacketBytes * ((refs + kPacketLanes - 1) / kPacketLanes));
  }

  bool over() const { return over_.load(std::memory_order_relaxed); }
  uint64_t bytes() const { return bytes_.load(std::memory_order_relaxed); }
  uint64_t max_bytes() const { return max_bytes_; }

 private:
  bool Add(uint64_t b) {
    if (max_bytes_ == 0) return true;
    if (bytes_.fetch_add(b, std::memory_order_relaxed) + b > max_bytes_) {
      over_.store(true, std::memory_order_relaxed);
    }
    return !over();
  }

  const uint64_t max_bytes_;
  std::atomic<uint64_t> bytes_{0};
  std::atomic<bool> over_{false};
};

}  // namespace kdtree

#endif  // KDTREE_CC_KDTREE_BUILD_BUDGET_H_
