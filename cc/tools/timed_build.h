// kdrt's timed builds, by the method of timed_render.h: one untimed warm-up
// build of each tracer (the first build in a process pays the kernel's
// first-touch zeroing of fresh pages, see cc/base/huge_pages.h), then timed
// rounds alternating the kd-tree and Embree, alone under the TimingLock.
#ifndef KDTREE_CC_TOOLS_TIMED_BUILD_H_
#define KDTREE_CC_TOOLS_TIMED_BUILD_H_

#include <memory>
#include <vector>

#include "absl/status/statusor.h"
#include "cc/base/timing_lock.h"
#include "cc/embree/embree_tracer.h"
#include "cc/geometry/triangle.h"
#include "cc/kdtree/builder.h"
#include "cc/tools/timed_render.h"

namespace kdtree {

struct TimedBuilds {
  absl::StatusOr<KdTree> tree = absl::UnknownError("not built");  // the last build
  std::unique_ptr<EmbreeTracer> embree;                           // the last build, or none
  double kd_warmup = 0, embree_warmup = 0;                        // seconds, untimed
  std::vector<double> kd_runs, embree_runs;                       // the timed rounds
};

// `embree` null: the kd-tree alone; `embree_rounds` false: Embree built once,
// untimed (its warm-up; b->embree_runs stays empty). Rounds repeat under
// MoreRuns(round totals, repeats, budget_s). Acquires `lock` for the rounds
// and releases it.
absl::Status TimeBuilds(const TriangleSoup& soup, const Config& config, const EmbreeOptions* embree,
                        bool embree_rounds, int repeats, double budget_s, TimingLock* lock, const StepFn& step, TimedBuilds* b);

}  // namespace kdtree

#endif  // KDTREE_CC_TOOLS_TIMED_BUILD_H_
