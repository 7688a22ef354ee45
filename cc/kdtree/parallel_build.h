// Parallel build that yields the serial tree, byte for byte.
//
// The top levels of the recursion run as oneTBB tasks (tbb::task_group): at a
// node of at least kParallelMinRefs references and depth below
// ParallelDepth(threads), the two children are built at once, each by its own
// builder into its own Fragment, reading its references in the order the
// serial partition produces straight from the parent's pool (the parent waits
// meanwhile). A node's split depends only on its references in that order, so
// each fragment equals the serial subtree up to a shift of its node and list
// indices. The parent keeps one placeholder node per child fragment; when all
// are done, Stitch() writes nodes and leaf lists once, in the depth-first
// order (left, then right) in which the serial build writes them: it first
// sizes every fragment's subtree, so each fragment knows where its nodes and
// lists start, and the fragments are then written at once, as tasks.
// Subtree parallelism of this kind: Shevtsov, Soupikov & Kapustin, "Highly
// parallel fast kd-tree construction for interactive ray tracing of dynamic
// scenes", Eurographics 2007 (their lower levels); upper-level parallelism
// over one node's references is not done here.
#ifndef KDTREE_CC_KDTREE_PARALLEL_BUILD_H_
#define KDTREE_CC_KDTREE_PARALLEL_BUILD_H_

#include <cstddef>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "cc/kdtree/list_tree.h"

namespace kdtree {

inline constexpr size_t kParallelMinRefs = 2048;

// Depth above which nodes spawn tasks: log2(threads) + 3 levels, 8 tasks per
// thread at the bottom, enough for the task scheduler to balance subtrees of
// unequal size. Each level below the root copies its references once (into
// the child fragments' pools), so deeper spawning costs memory traffic.
int ParallelDepth(int threads);

// A subtree built on its own: tree.nodes[0] is its root, tree.refs[0] its
// empty list. `children` are the fragments hanging under its placeholder
// nodes (local node index, fragment), in increasing node order.
struct Fragment {
  ListTree tree;
  std::vector<std::pair<uint32_t, std::unique_ptr<Fragment>>> children;
};

// Writes the whole tree of `root` and its nested fragments into out->nodes
// and out->refs (replacing them) and adds every fragment's counters into
// out->counters (peak_build_refs: the largest). Returns false when an index
// would exceed KdNode::kMaxIndex.
bool Stitch(const Fragment& root, ListTree* out);

}  // namespace kdtree

#endif  // KDTREE_CC_KDTREE_PARALLEL_BUILD_H_
