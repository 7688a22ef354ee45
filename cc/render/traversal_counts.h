// The counting pass: replays recorded rays through the kd-tree's counting
// traversal (cc/kdtree/traversal.h) to get the report's N_IT (triangle tests
// per ray) and N_TR (inner nodes visited per ray). Kept apart from the timed
// render so that T_R is always measured on the non-counting fast path; the
// rays are the very ones the timed render traced (it is deterministic).
#ifndef KDTREE_CC_RENDER_TRAVERSAL_COUNTS_H_
#define KDTREE_CC_RENDER_TRAVERSAL_COUNTS_H_

#include <cstdint>
#include <vector>

#include "cc/kdtree/traversal.h"
#include "cc/kdtree/tree.h"
#include "cc/render/cost_image.h"
#include "cc/render/ray_record.h"

namespace kdtree {

struct RayCounts {
  TraversalCounters by_kind[kNumRayKinds];  // indexed by RayKind
  TraversalCounters all;
  // Rays whose counted result differs from the recorded one (must be 0: the
  // counting and the fast traversal are the same template).
  uint64_t result_mismatches = 0;

  // Averages per ray (0 when there are no rays).
  double n_it() const { return all.rays ? double(all.triangle_tests) / all.rays : 0.0; }
  double n_tr() const { return all.rays ? double(all.inner_visits) / all.rays : 0.0; }
};

// Primary records with Intersect, shadow and AO records with Occluded. With
// `per_pixel` (sized to the frame), each ray's counts are also added to the
// pixel it came from.
RayCounts CountTraversal(const KdTree& tree, const std::vector<RayRecord>& records,
                         CostImage* per_pixel = nullptr);

}  // namespace kdtree

#endif  // KDTREE_CC_RENDER_TRAVERSAL_COUNTS_H_
