// kdrt's timed steps: repeated runs under a count and a time budget, and
// repeated renders of one tracer with their per-effect times.
#ifndef KDTREE_CC_TOOLS_TIMED_RENDER_H_
#define KDTREE_CC_TOOLS_TIMED_RENDER_H_

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "cc/geometry/triangle.h"
#include "cc/render/renderer.h"
#include "cc/render/tracer.h"
#include "cc/render/view.h"

namespace kdtree {

// Whether to time one more run: none yet, or fewer than `repeats` so far and
// (with a budget > 0) the runs so far took less than `budget_s` seconds in all.
bool MoreRuns(const std::vector<double>& runs, int repeats, double budget_s);

// Timed renders of one tracer: every run's total, primary, shadow and AO
// seconds, and the last run's result.
struct Timed {
  RenderResult last;
  std::vector<double> t_r, t_primary, t_shadow, t_ao;
};
// Renders under MoreRuns(repeats, budget_s); `step` (may be empty) is told
// "render i/repeats" before each run.
Timed TimeRenders(const TriangleSoup& soup, const Tracer& tracer, const View& view,
                  const RenderOptions& opt, int repeats, double budget_s,
                  const std::function<void(const std::string&)>& step);

// {"rays": n, "seconds": median, "seconds_runs": [...]} after `"name": `.
std::string EffectJson(const char* name, uint64_t rays, const std::vector<double>& runs);

}  // namespace kdtree

#endif  // KDTREE_CC_TOOLS_TIMED_RENDER_H_
