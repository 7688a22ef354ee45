// kdrt's untimed passes over the frame's rays, which are also the renders'
// warm-ups: the kd-tree's recording render (its rays and hits), the counting
// pass over the recorded rays (N_IT, N_TR: traversal_counts.h), the
// comparison passes that trace the recorded rays through Embree and the
// robust Embree (compare.h), the ray dump (ray_dump.h), and the replays'
// recording renders (replay_tracer.h).
#ifndef KDTREE_CC_TOOLS_KDRT_PASSES_H_
#define KDTREE_CC_TOOLS_KDRT_PASSES_H_

#include <string>

#include "absl/status/statusor.h"
#include "cc/embree/embree_tracer.h"
#include "cc/geometry/triangle.h"
#include "cc/kdtree/tree.h"
#include "cc/render/kdtree_tracer.h"
#include "cc/render/renderer.h"
#include "cc/render/traversal_counts.h"
#include "cc/render/view.h"
#include "cc/tools/kdrt_lanes.h"
#include "cc/tools/progress.h"
#include "nlohmann/json.hpp"

namespace kdtree {

// Files the passes write ('' = none).
struct PassOutputs {
  std::string cost_image;  // per-pixel N_TR / N_IT (cost_image.h; .npy.gz)
  std::string dump_rays;   // every ray and its kd-tree result (ray_dump.h)
};

// What the passes give the record.
struct UntimedResults {
  RayCounts counts;
  nlohmann::ordered_json disagreements, robust_disagreements;  // null when not compared
};

// The passes, on `tree` (traced by `kd`) with the renderer's options `ropt`;
// `embree` null: no comparison. Each lane's warm-up time is that of its
// pass (the kd-tree's recording render, Embree's comparison when
// `embree_timed`, the robust Embree's comparison, each replay's recording
// render), and every lane that must reproduce the kd-tree's image and hit
// counts (the kd-tree's modes, the replays) gets the recorded render as its
// `last`. Errors: a file that cannot be written.
absl::StatusOr<UntimedResults> UntimedPasses(const TriangleSoup& soup, const KdTree& tree,
                                             const KdTreeTracer& kd, const EmbreeTracer* embree,
                                             bool embree_timed, const View& view,
                                             const RenderOptions& ropt, const PassOutputs& outputs,
                                             LaneSet* set, Progress* progress);

}  // namespace kdtree

#endif  // KDTREE_CC_TOOLS_KDRT_PASSES_H_
