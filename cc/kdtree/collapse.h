// Removal of splits that do not pay off, and collapse of empty leaves.
//
// The report names this as missing (section "Pruning": after pruning, some
// splits separate nothing). A post-pass over the built tree, bottom-up, with
// the SAH cost model of Wald & Havran, "On building fast kd-trees for ray
// tracing, and on doing that in O(N log N)", IEEE RT 2006 (K_T, K_I of
// Config): an inner node whose subtree costs
//   K_T SA(n) + cost(left) + cost(right)
// at least as much as one leaf with the union of its leaves' triangles,
//   K_I |union| SA(n),
// becomes that leaf. An inner node whose two children are (or became) empty
// leaves always becomes one empty leaf (its cost as a leaf is 0). Only unions
// of at most kMaxCollapsedLeaf triangles are considered. A leaf holding the
// union of its sub-leaves is always correct: every triangle in it touches the
// node box.
#ifndef KDTREE_CC_KDTREE_COLLAPSE_H_
#define KDTREE_CC_KDTREE_COLLAPSE_H_

#include <cstdint>

#include "cc/kdtree/config.h"
#include "cc/kdtree/list_tree.h"

namespace kdtree {

inline constexpr uint32_t kMaxCollapsedLeaf = 64;

// Rewrites tree->nodes and tree->refs (depth-first order kept); returns the
// number of inner nodes removed.
uint64_t CollapseTree(const Config& config, ListTree* tree);

}  // namespace kdtree

#endif  // KDTREE_CC_KDTREE_COLLAPSE_H_
