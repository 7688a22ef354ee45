// Hybrid split search: binning near the root, the exact sweep below.
//
// After Wald & Havran, "On building fast kd-trees for ray tracing, and on
// doing that in O(N log N)", IEEE RT 2006 (section 6, on approximating the
// upper levels), and Hunt, Mark & Stoll, "Fast kd-tree construction with an
// adaptive error-bounded heuristic", IEEE RT 2006: nodes with more than
// Config::hybrid_threshold references use Config::hybrid_bins equal bins on
// each of x, y and z (binned_sah.h); smaller nodes, where most of the tree's
// nodes and most of its cost decisions are, use every event (sweep_sah.h).
#ifndef KDTREE_CC_KDTREE_HYBRID_SAH_H_
#define KDTREE_CC_KDTREE_HYBRID_SAH_H_

#include <cstddef>

#include "cc/kdtree/binned_sah.h"
#include "cc/kdtree/sweep_sah.h"

namespace kdtree {

Split FindHybridSahSplit(const BuildRef* refs, size_t n, const AABB& node_box,
                         const Config& config, BinScratch* bins, SweepScratch* sweep);

}  // namespace kdtree

#endif  // KDTREE_CC_KDTREE_HYBRID_SAH_H_
