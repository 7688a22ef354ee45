// The median of timed runs: the figure the report quotes of repeated timings.
#ifndef KDTREE_CC_BASE_MEDIAN_H_
#define KDTREE_CC_BASE_MEDIAN_H_

#include <algorithm>
#include <cstddef>
#include <vector>

namespace kdtree {

// The median of `values` (mean of the middle two for an even count; 0 for
// none).
inline double Median(std::vector<double> values) {
  if (values.empty()) return 0;
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

}  // namespace kdtree

#endif  // KDTREE_CC_BASE_MEDIAN_H_
