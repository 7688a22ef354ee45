// The median of timed runs, the figure the report quotes of repeated timings,
// and the paired ratios of two tracers' runs.
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

// num[i] / den[i] for each round both have: two tracers' times taken in the
// same round, so a slow stretch of the machine falls on both (their median is
// the paired ratio every benchmark reports).
inline std::vector<double> PairedRatios(const std::vector<double>& num,
                                        const std::vector<double>& den) {
  std::vector<double> out;
  for (size_t i = 0; i < num.size() && i < den.size(); ++i) out.push_back(num[i] / den[i]);
  return out;
}

// a[i] - b[i] for each round both have: a tracer's render less the replay of
// its mode in the same round (replay_tracer.h), its tracing time alone.
inline std::vector<double> LessPerRound(const std::vector<double>& a,
                                        const std::vector<double>& b) {
  std::vector<double> out;
  for (size_t i = 0; i < a.size() && i < b.size(); ++i) out.push_back(a[i] - b[i]);
  return out;
}

}  // namespace kdtree

#endif  // KDTREE_CC_BASE_MEDIAN_H_
