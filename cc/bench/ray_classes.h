// render_bench --classes: where a single-ray tracer's time goes, by what the
// rays do. The recorded rays of a render are split into classes, and each
// class is traced on its own, in a tight loop with no renderer around it, by
// every single-ray tracer, in rounds (the tracers in turn, their order
// rotating), so that tracers are compared per class, paired per round.
//
// The classes: camera rays that reach no node of the kd-tree (they miss its
// padded root box, so a tracer only sets them up), camera rays that reach it
// and hit nothing, camera rays that hit, shadow rays and ambient-occlusion
// rays. A secondary ray is told its origin triangle (its pixel's primary hit)
// when the variant leaves it untested (RenderVariant::skip_origin), as the
// renderer tells it.
//
// Traced alone, a class finds caches and branch predictors in the state its
// own rays leave, not the render's mix, so these times are a diagnosis, not
// a render's time: render_bench's rounds remain the measure of the targets.
#ifndef KDTREE_CC_BENCH_RAY_CLASSES_H_
#define KDTREE_CC_BENCH_RAY_CLASSES_H_

#include <cstdint>
#include <string>
#include <vector>

#include "cc/bench/bench_record.h"
#include "cc/bench/render_check.h"
#include "cc/geometry/ray.h"
#include "cc/kdtree/tree.h"
#include "cc/render/ray_record.h"

namespace kdtree {
namespace bench {

struct RayClass {
  std::string name;
  bool any_hit = false;                // Occluded (else Intersect)
  std::vector<Ray> rays;               // in the render's order
  std::vector<uint32_t> origin_tris;   // any-hit classes: each ray's origin triangle
};

// The non-empty classes of `recs` (a recording render's rays), in the order
// above: camera_no_node, camera_miss, camera_hit, shadow, ao. Whether a
// camera ray reaches a node is asked of `tree` (its traversal's counters).
std::vector<RayClass> ClassifyRays(const std::vector<RayRecord>& recs, const KdTree& tree);

// Each class traced by each tracer in `tracers` (single rays), `warmup`
// untimed rounds then `rounds` timed ones. Per class: its rays and, per
// tracer, ns per ray in each round (ns_runs) and their median; and for each
// tracer other than
// `reference`, the reference's time over its own, paired per round (median,
// min, max). `reference` may name none of them.
Json TimeRayClasses(const std::vector<RayClass>& classes,
                    const std::vector<RenderVariant>& tracers, const std::string& reference,
                    int warmup, int rounds);

}  // namespace bench
}  // namespace kdtree

#endif  // KDTREE_CC_BENCH_RAY_CLASSES_H_
