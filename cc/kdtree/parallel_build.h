// Parallel build that yields the serial tree, byte for byte.
//
// The top levels of the recursion run as oneTBB tasks (tbb::task_group): at a
// node of at least kParallelMinRefs references and depth below
// kParallelMaxDepth, the two children are built at once, each by its own
// builder into its own tree fragment, from a copy of its references in the
// order the serial partition produces. A node's split depends only on its
// references in that order, so each fragment equals the serial subtree up to
// a shift of its node and list indices. The fragments are then appended in
// depth-first order (left, then right), as the serial build writes them.
// Subtree parallelism of this kind: Shevtsov, Soupikov & Kapustin, "Highly
// parallel fast kd-tree construction for interactive ray tracing of dynamic
// scenes", Eurographics 2007 (their lower levels); upper-level parallelism
// over one node's references is not done here.
#ifndef KDTREE_CC_KDTREE_PARALLEL_BUILD_H_
#define KDTREE_CC_KDTREE_PARALLEL_BUILD_H_

#include <cstddef>

#include "cc/kdtree/tree.h"

namespace kdtree {

inline constexpr size_t kParallelMinRefs = 2048;
inline constexpr int kParallelMaxDepth = 12;

// Appends `fragment` (a subtree built on its own: nodes[0] is its root,
// refs[0] its empty list) at the end of tree->nodes and tree->refs, shifting
// child and list indices; counters are added (peak_build_refs: the larger).
// Returns false when an index would exceed KdNode::kMaxIndex.
bool AppendFragment(const KdTree& fragment, KdTree* tree);

}  // namespace kdtree

#endif  // KDTREE_CC_KDTREE_PARALLEL_BUILD_H_
