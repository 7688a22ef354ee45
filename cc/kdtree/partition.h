// The partition of a node's references into its two children (builder.cc).
//
// A reference goes left when its box starts before the split plane and right
// when it ends after it (both for a straddling one); a box lying in the plane
// (lo == hi == pos) goes to both sides, or nowhere in the seed-compatible mode
// (the report's strict partition, counted as lost_planar). With clipping
// (Havran's thesis, 2000, section 4.5; the report's "split clipping") a
// straddling triangle is cut at the plane and each part gets the box of the
// triangle's piece on its side (clipping.h), dropped when pruning finds it
// outside its child; with perfect splits (Havran & Bittner 2002; Wald &
// Havran 2006) each part's box is the exact box of the triangle inside the
// child (perfect_split.h). The sides are written in the order of the node's
// references, at two cursors the caller places (builder.cc: each reference
// yields at most one reference per side).
#ifndef KDTREE_CC_KDTREE_PARTITION_H_
#define KDTREE_CC_KDTREE_PARTITION_H_

#include <cstddef>

#include "cc/geometry/aabb.h"
#include "cc/geometry/triangle.h"
#include "cc/kdtree/build_ref.h"
#include "cc/kdtree/config.h"
#include "cc/kdtree/tree.h"

namespace kdtree {

template <class Ref>
struct Cursors {
  Ref* left;   // next free slot of the left side
  Ref* right;  // next free slot of the right side
};

// No clipping: references keep their boxes (BoxOf(r, boxes); boxes may be
// null for BuildRef). Four at a time in SSE, the cursors advanced by the
// tests' masks without a branch on the outcome.
template <class Ref>
void PartitionBoxes(const Ref* src, size_t count, const Split& split, const AABB* boxes,
                    bool seed_compatible, BuildCounters* counters, Cursors<Ref>* out);

// Clipping or perfect splits (config.use_clipping, config.perfect_splits):
// straddling triangles are cut; the other references as in PartitionBoxes.
// Counts N_CL (clipped) and the pruned parts (pruned_box).
void PartitionClipping(const TriangleSoup& soup, const Config& config, const BuildRef* src,
                       size_t count, const Split& split, const AABB& left_box,
                       const AABB& right_box, BuildCounters* counters, Cursors<BuildRef>* out);

}  // namespace kdtree

#endif  // KDTREE_CC_KDTREE_PARTITION_H_
