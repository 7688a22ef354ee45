// The recursive build of a kd-tree over references (Builder<Ref>): the
// node loop of BuildKdTree (builder.h) that finds a split (the strategies'
// files), partitions the references (partition.h), makes leaves (with exact
// pruning, pruning.h), builds large subtrees in parallel as fragments
// (parallel_build.h) and deep IndexRef subtrees from a local copy of their
// boxes. Internal to builder.cc; a header only because Builder is a template.
#ifndef KDTREE_CC_KDTREE_RECURSIVE_BUILDER_H_
#define KDTREE_CC_KDTREE_RECURSIVE_BUILDER_H_

#include <cassert>
#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "cc/kdtree/binned_sah.h"
#include "cc/kdtree/build_budget.h"
#include "cc/kdtree/build_ref.h"
#include "cc/kdtree/hybrid_sah.h"
#include "cc/kdtree/median_split.h"
#include "cc/kdtree/parallel_build.h"
#include "cc/kdtree/partition.h"
#include "cc/kdtree/pruning.h"
#include "cc/kdtree/ref_pool.h"
#include "cc/kdtree/sah_cost.h"
#include "cc/kdtree/sweep_sah.h"
#include "tbb/parallel_for.h"
#include "tbb/task_group.h"

namespace kdtree {
namespace build_internal {

// Runs f(chunk, begin, end) over kSetupChunks equal chunks of [0, n), on the
// arena's threads when `parallel`.
constexpr size_t kSetupChunks = 64;
template <class F>
void ForChunks(size_t n, bool parallel, const F& f) {
  const auto run = [&](size_t c) { f(c, c * n / kSetupChunks, (c + 1) * n / kSetupChunks); };
  if (parallel) {
    tbb::parallel_for(size_t{0}, kSetupChunks, run);
  } else {
    for (size_t c = 0; c < kSetupChunks; ++c) run(c);
  }
}

// Capacity reserved up front for the nodes, the leaf lists and the build
// references, in multiples of the triangle count. Large arrays come from mmap
// (cc/base/huge_pages.h), which backs only the pages written, so a generous
// reservation costs address space, not memory; a short one costs a copy of the
// whole array into fresh pages each time it grows (the report's trees hold 5
// to 8 references per triangle: N_TP, peak_build_refs).
constexpr size_t kReserveFactor = 8;

// IndexRef builds: a node of at most this many references (and at least
// kLocalMinRefs) is built from a local copy of its boxes (Builder::
// RecurseLocal): the deep levels of a scene of millions of triangles then scan
// one compact array that stays in cache, not boxes scattered over the whole
// scene's array (at about 15 ns per reference and level on a 7M-triangle
// scan). 64k boxes are 1.5 MB.
constexpr size_t kLocalMaxRefs = size_t{1} << 16;
constexpr size_t kLocalMinRefs = 1024;

// Ref is BuildRef (a triangle and the box of its part in the node) or
// IndexRef (a triangle whose box is boxes_[tri]).
template <class Ref>
class Builder {
  static constexpr bool kIndex = std::is_same<Ref, IndexRef>::value;

 public:
  // parallel_depth: nodes above it spawn their children as tasks
  // (parallel_build.h); 0 = serial. `boxes`: the triangles' tight boxes, for
  // IndexRef builders under the root builder (which makes them).
  Builder(const TriangleSoup& soup, const Config& config, Fragment* fragment, int max_depth,
          int parallel_depth, BuildBudget* budget, const AABB* boxes = nullptr)
      : soup_(soup),
        config_(config),
        fragment_(fragment),
        tree_(&fragment->tree),
        max_depth_(max_depth),
        parallel_depth_(parallel_depth),
        budget_(budget),
        boxes_(boxes) {}

  // Builds a subtree (a fragment, parallel_build.h) over `refs` into tree_.
  // Its root reads `refs` in place (the parent's pool, unchanged meanwhile).
  void RunFragment(const Ref* refs, size_t n, const AABB& box, int depth) {
    tree_->nodes.reserve(kReserveFactor * n + 1);
    tree_->refs.reserve(kReserveFactor * n + 1);
    tree_->refs.push_back(0);
    pool_->Reserve(kReserveFactor * n + 1);
    Recurse(0, n, box, depth, refs);
  }

  bool overflow() const { return overflow_; }

  // The whole tree; `parallel`: the first references are made by the
  // arena's threads (each chunk's box, then their union: min and max are
  // exact, so the root box does not depend on the chunks).
  absl::Status Run(bool parallel) {
    const size_t n = soup_.size();
    tree_->nodes.reserve(kReserveFactor * n + 1);
    tree_->refs.reserve(kReserveFactor * n + 1);
    tree_->refs.push_back(0);  // the shared list of every empty leaf
    pool_->Reserve(kReserveFactor * n + 1);
    Ref* first = pool_->Reserved(n);
    if constexpr (kIndex) {
      // One element more: the SSE loads of binned_sah.cc read a word past a
      // box.
      box_storage_.resize(n + 1);
      box_storage_[n] = AABB();
      boxes_ = box_storage_.data();
    }
    std::vector<AABB> chunk_box(kSetupChunks);
    ForChunks(n, parallel, [&](size_t chunk, size_t begin, size_t end) {
      AABB box;
      for (size_t i = begin; i < end; ++i) {
        const AABB b = soup_.Bounds(i);
        if constexpr (kIndex) {
          box_storage_[i] = b;
          first[i] = static_cast<IndexRef>(i);
        } else {
          first[i] = BuildRef{b, static_cast<uint32_t>(i)};
        }
        box.Extend(b);
      }
      chunk_box[chunk] = box;
    });
    AABB root;
    for (const AABB& b : chunk_box) root.Extend(b);
    pool_->Resize(n);
    tree_->bounds = root;
    Recurse(0, n, root, 0);
    if (budget_->over()) {
      return absl::ResourceExhaustedError(absl::StrFormat(
          "kd-tree would need more than the %.2f GB it may use (stopped at %.2f GB): "
          "lower maxDepth or raise maxLeafSize",
          budget_->max_bytes() / 1e9, budget_->bytes() / 1e9));
    }
    if (overflow_) {
      return absl::ResourceExhaustedError(absl::StrCat(
          "kd-tree exceeds 2^30 nodes or references (stopped at ", tree_->nodes.size(), " nodes, ",
          tree_->refs.size(), " references): lower maxDepth or raise maxLeafSize"));
    }
    return absl::OkStatus();
  }

 private:
  // The node over pool_[begin, end), or over external[0, end - begin) when
  // given (a fragment's root).
  void Recurse(size_t begin, size_t end, const AABB& box, int depth,
               const Ref* external = nullptr) {
    const size_t count = end - begin;
    if constexpr (kIndex) {
      // Not in a builder that is local already, nor where the node's children
      // would be built in parallel.
      if (tri_map_ == nullptr && count <= kLocalMaxRefs && count >= kLocalMinRefs &&
          !(count >= kParallelMinRefs && depth < parallel_depth_)) {
        RecurseLocal(external != nullptr ? external : pool_->data() + begin, count, box, depth);
        return;
      }
    }
    const uint32_t node = static_cast<uint32_t>(tree_->nodes.size());
    tree_->nodes.push_back(KdNode::Leaf(0));
    // Past the index range (2^30 nodes or references) the build has failed:
    // stop growing (the node stays an empty leaf) instead of recursing on.
    if (overflow_ || !budget_->AddNode() || tree_->nodes.size() > KdNode::kMaxIndex ||
        tree_->refs.size() > KdNode::kMaxIndex) {
      overflow_ = true;
      return;
    }
    if (count <= static_cast<size_t>(config_.max_leaf_size) || depth >= max_depth_) {
      MakeLeaf(node, external != nullptr ? external : pool_->data() + begin, count, box);
      return;
    }
    const Split split =
        FindSplit(external != nullptr ? external : pool_->data() + begin, count, box);
    // Full SAH: split only when it is cheaper than a leaf (sah_cost.h).
    if (!split.found ||
        (config_.full_sah && !(static_cast<double>(split.cost) < LeafCost(count, config_)))) {
      MakeLeaf(node, external != nullptr ? external : pool_->data() + begin, count, box);
      return;
    }
    const AABB left_box = box.LeftOf(split.axis, split.pos);
    const AABB right_box = box.RightOf(split.axis, split.pos);
    const size_t left_begin = pool_->size();
    Partition(begin, end, external, split, left_box, right_box);
    const size_t right_begin = left_begin + count;  // see Partition
    const size_t right_end = pool_->size();
    if (pool_->size() > counters().peak_build_refs) {
      counters().peak_build_refs = pool_->size();
      counters().peak_build_bytes =
          pool_->size() * sizeof(Ref) + (kIndex ? (soup_.size() + 1) * sizeof(AABB) : 0);
    }

    if (count >= kParallelMinRefs && depth < parallel_depth_) {
      RecurseInParallel(node, left_begin, left_begin + left_count_, right_begin, right_end,
                        left_box, right_box, depth, split);
      return;
    }
    Recurse(left_begin, left_begin + left_count_, left_box, depth + 1);
    const size_t right_node = tree_->nodes.size();
    if (right_node > KdNode::kMaxIndex) overflow_ = true;
    tree_->nodes[node] =
        KdNode::Inner(split.axis, split.pos, static_cast<uint32_t>(right_node & KdNode::kMaxIndex));
    Recurse(right_begin, right_end, right_box, depth + 1);
    pool_->Resize(left_begin);
  }

  // The subtree over refs[0, count) built by a local builder into the same
  // tree (nodes and lists are appended in the same depth-first order): its
  // references are 0 .. count - 1 into a copy of their boxes in the node's
  // order, and tri_map_ turns them back into triangles at the leaves. The
  // same boxes in the same order give the same splits, partitions and lists,
  // hence the same tree. The local builder and its arrays are kept for the
  // next such subtree.
  void RecurseLocal(const Ref* refs, size_t count, const AABB& box, int depth) {
    if constexpr (kIndex) {
      if (local_ == nullptr) {
        local_ = std::make_unique<Builder>(soup_, config_, fragment_, max_depth_, 0, budget_);
        local_->pool_ = pool_;  // its references go on top of this builder's
      }
      // `refs` may lie in the pool: read them before the pool grows.
      local_boxes_.resize(count + 1);  // + 1: binned_sah.cc's SSE loads
      local_tris_.resize(count);
      for (size_t i = 0; i < count; ++i) {
        local_boxes_[i] = boxes_[refs[i]];
        local_tris_[i] = refs[i];
      }
      local_boxes_[count] = AABB();
      const size_t begin = pool_->size();
      Ref* first = pool_->Reserved(count);
      for (size_t i = 0; i < count; ++i) first[i] = static_cast<IndexRef>(i);
      pool_->Resize(begin + count);
      local_->boxes_ = local_boxes_.data();
      local_->tri_map_ = local_tris_.data();
      local_->Recurse(begin, begin + count, box, depth);
      pool_->Resize(begin);
      if (local_->overflow_) overflow_ = true;
    }
  }

  Split FindSplit(const Ref* refs, size_t count, const AABB& box) {
    if (!config_.use_binning) return FindMedianSplit(box);
    if constexpr (kIndex) {
      assert(config_.split_method == Config::SplitMethod::kBinned);  // builder.cc's UsesIndexRefs
      return FindBinnedSahSplit(refs, boxes_, count, box, config_, &scratch_);
    } else {
      switch (config_.split_method) {
        case Config::SplitMethod::kSweep:
          return FindSweepSahSplit(refs, count, box, config_, &sweep_);
        case Config::SplitMethod::kHybrid:
          return FindHybridSahSplit(refs, count, box, config_, &scratch_, &sweep_);
        case Config::SplitMethod::kBinned:
          break;
      }
      return FindBinnedSahSplit(refs, count, box, config_, &scratch_);
    }
  }

  // The two children as two fragments built at once (parallel_build.h),
  // under two placeholder nodes.
  void RecurseInParallel(uint32_t node, size_t left_begin, size_t left_end, size_t right_begin,
                         size_t right_end, const AABB& left_box, const AABB& right_box, int depth,
                         const Split& split) {
    assert(tree_->nodes.size() == size_t{node} + 1);
    if (size_t{node} + 2 > KdNode::kMaxIndex) overflow_ = true;
    tree_->nodes[node] = KdNode::Inner(split.axis, split.pos, (node + 2) & KdNode::kMaxIndex);
    tree_->nodes.push_back(KdNode::Leaf(0));  // left placeholder
    tree_->nodes.push_back(KdNode::Leaf(0));  // right placeholder
    auto left = std::make_unique<Fragment>();
    auto right = std::make_unique<Fragment>();
    Builder lb(soup_, config_, left.get(), max_depth_, parallel_depth_, budget_, boxes_);
    Builder rb(soup_, config_, right.get(), max_depth_, parallel_depth_, budget_, boxes_);
    const Ref* refs = pool_->data();
    tbb::task_group group;
    group.run(
        [&] { lb.RunFragment(refs + left_begin, left_end - left_begin, left_box, depth + 1); });
    rb.RunFragment(refs + right_begin, right_end - right_begin, right_box, depth + 1);
    group.wait();
    pool_->Resize(left_begin);
    if (lb.overflow() || rb.overflow()) overflow_ = true;
    fragment_->children.emplace_back(node + 1, std::move(left));
    fragment_->children.emplace_back(node + 2, std::move(right));
  }

  // Appends 2 count slots to the pool: the left references from the first,
  // the right ones from slot `count`, each side in the order of the node's
  // references (left_count_ of them on the left, the right side ends at the
  // pool's new end). Every reference yields at most one left and one right
  // reference, so neither side can overrun the other; the slots between them
  // stay unused until the node is done (a copy of the right side next to the
  // left one cost 5 % of a binned build).
  void Partition(size_t begin, size_t end, const Ref* external, const Split& split,
                 const AABB& left_box, const AABB& right_box) {
    const size_t count = end - begin;
    Ref* const left_first = pool_->Reserved(2 * count);
    Ref* const right_first = left_first + count;
    // Stable: no growth below.
    const Ref* const src = external != nullptr ? external : pool_->data() + begin;
    Cursors<Ref> out{left_first, right_first};
    if constexpr (kIndex) {
      PartitionBoxes(src, count, split, boxes_, config_.seed_compatible, &counters(), &out);
    } else if (config_.use_clipping || config_.perfect_splits) {
      PartitionClipping(soup_, config_, src, count, split, left_box, right_box, &counters(), &out);
    } else {
      PartitionBoxes(src, count, split, boxes_, config_.seed_compatible, &counters(), &out);
    }
    left_count_ = static_cast<size_t>(out.left - left_first);
    const size_t right_count = static_cast<size_t>(out.right - right_first);
    pool_->Resize(pool_->size() + count + right_count);
  }

  void MakeLeaf(uint32_t node, const Ref* leaf_refs, size_t n, const AABB& box) {
    HugeBuffer<uint32_t>& refs = tree_->refs;
    const size_t offset = refs.size();
    refs.push_back(0);
    uint32_t count = 0;
    for (size_t i = 0; i < n; ++i) {
      const uint32_t t = tri_map_ != nullptr ? tri_map_[TriOf(leaf_refs[i])] : TriOf(leaf_refs[i]);
      if (config_.use_pruning && config_.exact_pruning) {
        const bool overlaps =
            config_.seed_compatible
                ? TriangleOverlapsBoxFloat(soup_.a(t), soup_.b(t), soup_.c(t), box)
                : TriangleOverlapsBoxConservative(soup_.a(t), soup_.b(t), soup_.c(t), box);
        if (!overlaps) {
          ++counters().pruned_leaf;
          continue;
        }
      }
      refs.push_back(t);
      ++count;
    }
    if (count == 0) {
      refs.pop_back();
      tree_->nodes[node] = KdNode::Leaf(0);
      return;
    }
    refs[offset] = count;
    if (!budget_->AddLeaf(count)) overflow_ = true;
    if (offset > KdNode::kMaxIndex) overflow_ = true;
    tree_->nodes[node] = KdNode::Leaf(static_cast<uint32_t>(offset & KdNode::kMaxIndex));
  }

  BuildCounters& counters() { return tree_->counters; }

  const TriangleSoup& soup_;
  const Config& config_;
  Fragment* fragment_;
  ListTree* tree_;
  RefPoolOf<Ref> own_pool_;
  RefPoolOf<Ref>* pool_ = &own_pool_;  // a local builder's is its parent's
  size_t left_count_ = 0;
  const int max_depth_;
  const int parallel_depth_;
  BuildBudget* budget_;             // the whole tree's, shared
  const AABB* boxes_;               // IndexRef: the tight boxes, by triangle
  HugeBuffer<AABB> box_storage_;    // the root builder's boxes_
  // A local builder (RecurseLocal): its references index boxes_ and
  // tri_map_, which gives their triangles. Null elsewhere.
  const uint32_t* tri_map_ = nullptr;
  std::unique_ptr<Builder> local_;  // reused for every local subtree
  std::vector<AABB> local_boxes_;
  std::vector<uint32_t> local_tris_;
  BinScratch scratch_;
  SweepScratch sweep_;
  bool overflow_ = false;
};

}  // namespace build_internal
}  // namespace kdtree

#endif  // KDTREE_CC_KDTREE_RECURSIVE_BUILDER_H_
