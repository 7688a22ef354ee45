// The builders' product: the report's tree, whose leaves point at lists of
// triangle indices (section "Spatial median kd-tree" of the report). A leaf's
// `bits >> 2` points into `refs` at a count followed by that many triangle
// indices (a count-prefixed list); all empty leaves share the single count 0
// stored at refs[0]. BuildKdTree (builder.h) lays the lists out as the
// finished KdTree's leaf packets (leaf_layout.h) and then frees them.
#ifndef KDTREE_CC_KDTREE_LIST_TREE_H_
#define KDTREE_CC_KDTREE_LIST_TREE_H_

#include <cstdint>

#include "cc/base/huge_pages.h"
#include "cc/geometry/aabb.h"
#include "cc/kdtree/tree.h"

namespace kdtree {

struct ListTree {
  AABB bounds;                // root box: union of the triangles' tight boxes
  HugeBuffer<KdNode> nodes;   // nodes[0] is the root
  HugeBuffer<uint32_t> refs;  // count-prefixed leaf lists; refs[0] == 0
  BuildCounters counters;

  const uint32_t* LeafBegin(const KdNode& leaf) const { return &refs[leaf.index() + 1]; }
  uint32_t LeafCount(const KdNode& leaf) const { return refs[leaf.index()]; }
};

}  // namespace kdtree

#endif  // KDTREE_CC_KDTREE_LIST_TREE_H_
