// kdrt's timed lanes (timed_render.h Lane): which tracers and render modes a
// run times in its rounds, in the order the record finds them by name
// (kdrt_record.h's lane names).
#ifndef KDTREE_CC_TOOLS_KDRT_LANES_H_
#define KDTREE_CC_TOOLS_KDRT_LANES_H_

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "absl/status/statusor.h"
#include "cc/embree/embree_tracer.h"
#include "cc/geometry/triangle.h"
#include "cc/kdtree/tree.h"
#include "cc/render/kdtree_tracer.h"
#include "cc/render/renderer.h"
#include "cc/render/replay_tracer.h"
#include "cc/render/tracer.h"
#include "cc/tools/kdrt_record.h"
#include "cc/tools/timed_render.h"

namespace kdtree {

// What a run times beside the kd-tree under the report's rules.
struct LaneChoice {
  bool fast = false;           // --fast_render: the fastest mode and our other single-ray mode
  bool embree_timed = false;   // Embree (`embree`) timed in the same rounds
  bool embree_robust = false;  // also Embree built robust (with fast and embree_timed)
  bool triangle_bvh = false;   // also the baseline over whole triangles (with fast)
  // With fast: the bytes the BVH over the tree's leaves may hold (its own
  // leaf packets: cc/kdtree/leaf_bvh.h), what the memory budget leaves
  // after the renders and the tree.
  uint64_t bvh_budget = ~uint64_t{0};
  RenderOptions render;        // the kd-tree's options (threads, shadow rays)
};

// The lanes and the tracers only they use. A lane points at its tracer, so
// the set must outlive its lanes' renders; moving it keeps the pointers.
struct LaneSet {
  std::vector<Lane> lanes;
  size_t embree_lane = 0;  // index of Embree's single-ray lane (when timed)
  size_t robust_lane = 0;  // index of the robust Embree's first lane (when built)
  std::unique_ptr<EmbreeTracer> robust;  // Embree built with RTC_SCENE_FLAG_ROBUST, or null
  // With `fast`: the tree's leaves under a BVH (cc/kdtree/leaf_bvh.h), the
  // third single-ray mode, and the seconds its build took.
  std::unique_ptr<KdTreeBvhTracer> bvh;
  BuiltBvh bvh_built;  // kept after it is freed
  // With `fast` and `triangle_bvh`: the same kernels over a BVH of whole
  // triangles (cc/kdtree/triangle_bvh.h), its build's seconds and its bytes.
  std::unique_ptr<TriangleBvhTracer> triangle_bvh;
  double triangle_bvh_build_s = 0;
  size_t triangle_bvh_bytes = 0;
  std::unique_ptr<ReplayTracer> replay_single, replay_packets;  // or null
};

// In order: the kd-tree (the report's rules); with `fast` its fastest mode
// (packets of 4x4 pixels, shadow rays leaving their origin triangle untested
// and searched from the light: RenderOptions::skip_origin) and those shadow
// rays one at a time, then the same rays one at a time through the BVH over
// `tree`'s leaves (kd-tree's tracer is on `tree`), and with `triangle_bvh`
// both modes' rays through a BVH of whole triangles; Embree's single rays when timed, and with `fast` its
// packet calls on the same blocks (rtcIntersect16 with the coherent flag,
// rtcOccluded16: its best mode is the faster of the two, #23's fair bar);
// with `fast` and `embree_robust` a second Embree built robust (`eo` with
// robust set), single rays and packets; with `fast`, Embree timed and one
// thread, the kd-tree's answers replayed (replay_tracer.h: the renderer's
// own work), single rays and packets, for each pass's tracing time alone
// (record fast_render.passes). `embree` may be null when not timed.
absl::StatusOr<LaneSet> MakeLanes(const TriangleSoup& soup, const KdTree& tree, const Tracer& kd,
                                  const EmbreeTracer* embree, const EmbreeOptions& eo,
                                  const LaneChoice& choice);

}  // namespace kdtree

#endif  // KDTREE_CC_TOOLS_KDRT_LANES_H_
