// kdrt's timed builds, by the method of timed_render.h: one untimed warm-up
// build of each tracer (the first build in a process pays the kernel's
// first-touch zeroing of fresh pages, see cc/base/huge_pages.h), then timed
// rounds alternating the kd-tree and Embree, alone under the TimingLock.
#ifndef KDTREE_CC_TOOLS_TIMED_BUILD_H_
#define KDTREE_CC_TOOLS_TIMED_BUILD_H_

#include <memory>
#include <vector>

#include "absl/status/statusor.h"
#include "cc/embree/embree_tracer.h"
#include "cc/geometry/triangle.h"
#include "cc/kdtree/builder.h"
#include "cc/tools/timed_render.h"

namespace kdtree {

struct TimedBuilds {
  BuildLimits limits;  // set by the caller: what each kd-tree build may hold
  absl::StatusOr<KdTree> tree = absl::UnknownError("not built");  // the last build
  std::unique_ptr<EmbreeTracer> embree;                           // the last build, or none
  double kd_warmup = 0, embree_warmup = 0;                        // seconds, untimed
  std::vector<double> kd_runs, embree_runs;                       // the timed rounds
};

// The untimed warm-up build of each tracer (`embree` null: the kd-tree
// alone), kept in *b for the renders.
absl::Status WarmUpBuilds(const TriangleSoup& soup, const Config& config, const EmbreeOptions* embree,
                          TimedBuilds* b);

// Timed rounds alternating the kd-tree and (unless null) Embree, repeated
// under MoreRuns(round totals, repeats, budget_s); the caller holds the
// TimingLock. Each build first frees the tracer's last one (b->tree,
// b->embree), so a process never holds two trees of a tracer: tracers taken
// from *b before are gone after.
absl::Status TimeBuildRounds(const TriangleSoup& soup, const Config& config, const EmbreeOptions* embree,
                             int repeats, double budget_s, const StepFn& step, TimedBuilds* b);

}  // namespace kdtree

#endif  // KDTREE_CC_TOOLS_TIMED_BUILD_H_
