#include "cc/kdtree/hybrid_sah.h"

namespace kdtree {

Split FindHybridSahSplit(const BuildRef* refs, size_t n, const AABB& node_box,
                         const Config& config, BinScratch* bins, SweepScratch* sweep) {
  if (n > static_cast<size_t>(config.hybrid_threshold)) {
    Config binned = config;
    binned.bins = config.hybrid_bins;
    binned.use_driving_axis = false;
    return FindBinnedSahSplit(refs, n, node_box, binned, bins);
  }
  return FindSweepSahSplit(refs, n, node_box, config, sweep);
}

}  // namespace kdtree
