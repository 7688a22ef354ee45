#include "cc/tools/kdrt_passes.h"

#include <cstdio>
#include <utility>
#include <vector>

#include "cc/render/compare.h"
#include "cc/render/cost_image.h"
#include "cc/render/ray_dump.h"
#include "cc/tools/paths.h"

namespace kdtree {

absl::StatusOr<UntimedResults> UntimedPasses(const TriangleSoup& soup, const KdTree& tree,
                                             const KdTreeTracer& kd, const EmbreeTracer* embree,
                                             bool embree_timed, const View& view,
                                             const RenderOptions& ropt, const PassOutputs& outputs,
                                             LaneSet* set, Progress* progress) {
  UntimedResults out;
  std::vector<Lane>& lanes = set->lanes;
  progress->Phase("stats", "recording rays");
  RenderOptions rec_opt = ropt;
  rec_opt.record_rays = true;
  RenderResult recorded = Render(soup, kd, view, rec_opt);
  lanes.front().warmup_s = recorded.seconds;
  progress->Phase("recording render (kd-tree warm-up)", "counting pass");
  const bool costs = !outputs.cost_image.empty();
  CostImage cost(costs ? view.width : 0, costs ? view.height : 0);
  out.counts = CountTraversal(tree, recorded.rays, costs ? &cost : nullptr);
  progress->Phase("counting pass");
  if (costs) {
    absl::Status st = WriteCreatingDirectory(
        outputs.cost_image, [&](const std::string& p) { return WriteCostImageNpyGz(p, cost); });
    if (!st.ok()) return st;
    progress->Phase("cost image");
  }
  if (embree != nullptr) {
    progress->Step("comparing with embree");
    const Disagreements d = CompareTracers(recorded.rays, soup, kd, *embree);
    out.disagreements = d.ToJson();
    for (const std::string& ex : d.examples) std::fprintf(stderr, "kdrt: disagreement: %s\n", ex.c_str());
    progress->Phase("embree comparison (embree warm-up)");
    if (embree_timed) {
      lanes[set->embree_lane].warmup_s = progress->phases()["embree comparison (embree warm-up)"].get<double>();
    }
    if (set->robust != nullptr) {
      progress->Step("comparing with embree (robust)");
      out.robust_disagreements = CompareTracers(recorded.rays, soup, kd, *set->robust).ToJson();
      progress->Phase("embree robust comparison (its warm-up)");
      lanes[set->robust_lane].warmup_s =
          progress->phases()["embree robust comparison (its warm-up)"].get<double>();
    }
  }
  if (!outputs.dump_rays.empty()) {
    progress->Step("writing ray dump");
    RayDump dump{view.width, view.height, std::move(recorded.rays)};
    if (absl::Status st = WriteRayDump(outputs.dump_rays, dump); !st.ok()) return st;
    progress->Phase("ray dump");
  }
  recorded.rays = std::vector<RayRecord>();
  for (Lane& l : lanes) {
    // Our tracers give the kd-tree's answers bit for bit, in every mode: each
    // of their lanes must reproduce its image and hit counts.
    const bool ours = l.tracer == &kd || l.tracer == set->bvh.get() ||
                      l.tracer == set->triangle_bvh.get();
    if (ours || l.replay != nullptr) l.last = recorded;  // to reproduce
    if (l.replay != nullptr) {  // its answers, recorded in its mode (its warm-up)
      l.replay->Record();
      l.warmup_s = Render(soup, *l.replay, view, l.opt).seconds;
    }
  }
  return out;
}

}  // namespace kdtree
