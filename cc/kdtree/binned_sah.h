// Binned SAH split with min-max binning.
//
// Report, section "Binning SAH strategy"; min-max binning as in Hapala &
// Havran, "Review: Kd-tree traversal algorithms for ray tracing", CGF 30(1),
// 2011 (the report's [1]); SAH after Havran & Bittner 2002 (the report's [2]).
// Two arrays of `bins` counters receive, in one pass over the references, the
// bin of each box's start (min) and end (max). One sweep over the bins - 1
// interior planes then evaluates the report's relaxed cost
//     C = SA_L * N_L + SA_R * N_R
// with N_L += starts[i], N_R -= ends[i]. The first strict minimum wins; with
// all three axes, they are tried in x, y, z order. There is no cost-based
// termination (as in the report): a node splits until maxDepth/maxLeafSize.
// With Config::full_sah the cost is Wald & Havran's full SAH (sah_cost.h).
#ifndef KDTREE_CC_KDTREE_BINNED_SAH_H_
#define KDTREE_CC_KDTREE_BINNED_SAH_H_

#include <cstddef>
#include <cstdint>
#include <vector>

#include "cc/geometry/aabb.h"
#include "cc/kdtree/build_ref.h"
#include "cc/kdtree/config.h"

namespace kdtree {

// Reused counter arrays, so that the build allocates nothing per node.
struct BinScratch {
  std::vector<uint32_t> starts, ends;
  std::vector<float> n_left, n_right, cost, plane;  // per candidate plane
};

// Bin of coordinate x: (int)((x - lo) * bins / extent), clamped to
// [0, bins - 1]. Float arithmetic in this order (seed-compatible).
inline int BinOf(float x, float lo, float extent, int bins) {
  const float f = (x - lo) * static_cast<float>(bins) / extent;
  // Clamp before converting: a reference box may reach far beyond a tiny node
  // (f up to +inf), and converting a float beyond INT_MAX to int is undefined
  // (INT_MIN on x86: a write before the bins). Same bins as before otherwise.
  if (!(f >= 0.0f)) return 0;  // negative or NaN
  if (!(f < static_cast<float>(bins))) return bins - 1;
  return static_cast<int>(f);
}

// Position of candidate plane i (1 <= i < bins) of an axis [lo, lo + extent].
inline float BinPlane(float lo, float extent, int i, int bins) {
  return lo + extent * static_cast<float>(i) / static_cast<float>(bins);
}

// Start and end bins of every reference on the three axes in one pass:
// starts[axis * bins + BinOf(box.lo[axis], ...)] and likewise ends with
// box.hi, exactly the bins of the scalar BinOf (SSE, four lanes). The
// counts are the first 3 bins entries of scratch->starts and ->ends (the
// arrays are longer: partial histograms are summed into them).
void CountBinsAllAxes(const BuildRef* refs, size_t n, const AABB& box, int bins,
                      BinScratch* scratch);

// Best plane over config.bins bins on the driving axis (config.use_driving_axis)
// or on all three axes. Axes of zero extent are skipped; not found when every
// candidate axis is flat.
Split FindBinnedSahSplit(const BuildRef* refs, size_t n, const AABB& node_box,
                         const Config& config, BinScratch* scratch);

// The same over triangle indices whose boxes are boxes[tri] (build_ref.h): the
// split FindBinnedSahSplit returns for BuildRefs holding those boxes. `boxes`
// has one element past the last triangle's (the SSE loads read a word past a
// box).
Split FindBinnedSahSplit(const IndexRef* refs, const AABB* boxes, size_t n, const AABB& node_box,
                         const Config& config, BinScratch* scratch);

}  // namespace kdtree

#endif  // KDTREE_CC_KDTREE_BINNED_SAH_H_
