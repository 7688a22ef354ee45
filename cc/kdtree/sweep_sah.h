// Exact SAH split by an event sweep.
//
// I. Wald and V. Havran, "On building fast kd-trees for ray tracing, and on
// doing that in O(N log N)", IEEE Symposium on Interactive Ray Tracing 2006,
// section 4.2-4.3. Every reference gives, per axis, a start event at box.lo
// and an end event at box.hi, or a single planar event when lo == hi (a
// triangle lying in a plane of that axis). Events are sorted by position, and
// at equal position ends before planars before starts. One sweep then knows,
// at each distinct position P, exactly the counts the builder's partition
// produces (builder.h):
//   N_L = #(lo < P) + #(planar at P),  N_R = #(hi > P) + #(planar at P)
// (in-plane triangles go to both children in the default mode). Candidates:
// every event position P strictly inside the node box, and the floats just
// below and just above P (when no other event lies there). Between two events
// the counts are constant and the cost is linear in the position, so these
// are all the planes that can be best: no float plane is missed, unlike
// binning. The float just above a planar event puts the triangles lying in P
// on the left only, the one just below on the right only (as Wald & Havran's
// choice of side for planar triangles, with the builder's plain partition).
// The first strict minimum wins, axes in x, y, z order.
//
// Complexity: this form sorts each node's events (O(N log^2 N) for the tree
// with a comparison sort); it finds the same plane as the paper's O(N log N)
// variant, which keeps the event lists sorted through the recursion. The
// events are 34-bit keys, so a node of many sorts them by radix in three
// linear passes (the same order: equal keys are the same event).
#ifndef KDTREE_CC_KDTREE_SWEEP_SAH_H_
#define KDTREE_CC_KDTREE_SWEEP_SAH_H_

#include <cstddef>
#include <cstdint>
#include <vector>

#include "cc/geometry/aabb.h"
#include "cc/kdtree/build_ref.h"
#include "cc/kdtree/config.h"

namespace kdtree {

// Reused arrays (no per-node allocation once they have grown): the events,
// the radix sort's second buffer and its digit counts.
struct SweepScratch {
  std::vector<uint64_t> events, sorted;
  std::vector<uint32_t> counts;
};

// Best plane over every event of the three axes, under SplitCost (sah_cost.h).
// Not found when no event lies strictly inside the node box.
Split FindSweepSahSplit(const BuildRef* refs, size_t n, const AABB& node_box,
                        const Config& config, SweepScratch* scratch);

}  // namespace kdtree

#endif  // KDTREE_CC_KDTREE_SWEEP_SAH_H_
