// Spatial median split (the report's first kd-tree, section "Spatial median
// kd-tree"): the midpoint of the node box on the axis of largest extent.
#ifndef KDTREE_CC_KDTREE_MEDIAN_SPLIT_H_
#define KDTREE_CC_KDTREE_MEDIAN_SPLIT_H_

#include "cc/geometry/aabb.h"
#include "cc/kdtree/build_ref.h"

namespace kdtree {

// Axis of largest extent (ties to the lower axis); not found when the node box
// is a point (nothing left to split).
Split FindMedianSplit(const AABB& node_box);

}  // namespace kdtree

#endif  // KDTREE_CC_KDTREE_MEDIAN_SPLIT_H_
