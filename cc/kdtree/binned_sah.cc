#include "cc/kdtree/binned_sah.h"

#include <algorithm>

#include "cc/kdtree/sah_cost.h"

namespace kdtree {
namespace {

// Sweeps one axis; updates *best when a candidate is strictly cheaper.
void SweepAxis(const BuildRef* refs, size_t n, const AABB& box, int axis, int bins,
               const Config& config, BinScratch* s, Split* best) {
  const float lo = box.lo[axis];
  const float extent = box.hi[axis] - lo;
  if (!(extent > 0.0f)) return;
  s->starts.assign(bins, 0);
  s->ends.assign(bins, 0);
  for (size_t i = 0; i < n; ++i) {
    ++s->starts[BinOf(refs[i].box.lo[axis], lo, extent, bins)];
    ++s->ends[BinOf(refs[i].box.hi[axis], lo, extent, bins)];
  }
  float n_left = 0.0f, n_right = static_cast<float>(n);
  for (int i = 0; i + 1 < bins; ++i) {
    n_left += static_cast<float>(s->starts[i]);
    n_right -= static_cast<float>(s->ends[i]);
    const float plane = BinPlane(lo, extent, i + 1, bins);
    const float cost = SplitCost(box, axis, plane, n_left, n_right, config);
    if (!best->found || cost < best->cost) {
      best->found = true;
      best->axis = axis;
      best->pos = plane;
      best->cost = cost;
    }
  }
}

}  // namespace

Split FindBinnedSahSplit(const BuildRef* refs, size_t n, const AABB& node_box,
                         const Config& config, BinScratch* scratch) {
  Split best;
  if (config.use_driving_axis) {
    SweepAxis(refs, n, node_box, node_box.LongestAxis(), config.bins, config, scratch, &best);
  } else {
    for (int axis = 0; axis < 3; ++axis) {
      SweepAxis(refs, n, node_box, axis, config.bins, config, scratch, &best);
    }
  }
  return best;
}

}  // namespace kdtree
