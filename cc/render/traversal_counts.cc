#include "cc/render/traversal_counts.h"

namespace kdtree {

RayCounts CountTraversal(const KdTree& tree, const std::vector<RayRecord>& records,
                         CostImage* per_pixel) {
  RayCounts counts;
  for (const RayRecord& rec : records) {
    TraversalCounters ray_counts;
    TraversalCounters* c = &ray_counts;
    const Ray ray = rec.ray();
    if (rec.kind == RayKind::kPrimary) {
      const Hit hit = Intersect(tree, ray, {}, c);
      const bool same = hit.hit() == (rec.hit != 0) && (!hit.hit() || (hit.tri == rec.tri && hit.t == rec.t));
      counts.result_mismatches += !same;
    } else {
      counts.result_mismatches += Occluded(tree, ray, {}, c) != (rec.hit != 0);
    }
    counts.by_kind[static_cast<int>(rec.kind)].Add(ray_counts);
    if (per_pixel != nullptr) {
      per_pixel->Add(rec.pixel, rec.kind, ray_counts.inner_visits, ray_counts.triangle_tests);
    }
  }
  for (const TraversalCounters& c : counts.by_kind) counts.all.Add(c);
  return counts;
}

}  // namespace kdtree
