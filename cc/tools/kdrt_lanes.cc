#include "cc/tools/kdrt_lanes.h"

#include <memory>
#include <utility>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/time/clock.h"
#include "absl/time/time.h"
#include "cc/kdtree/leaf_bvh.h"
#include "cc/render/kdtree_tracer.h"
#include "cc/tools/kdrt_record.h"

namespace kdtree {

absl::StatusOr<LaneSet> MakeLanes(const TriangleSoup& soup, const KdTree& tree, const Tracer& kd,
                                  const EmbreeTracer* embree, const EmbreeOptions& eo,
                                  const LaneChoice& choice) {
  LaneSet set;
  std::vector<Lane>& lanes = set.lanes;
  const RenderOptions& ropt = choice.render;
  lanes.push_back({"kd-tree", &kd, ropt});
  RenderOptions fo = ropt;
  fo.packets = true;
  fo.skip_origin = true;
  if (choice.fast) {
    lanes.push_back({kFastLane, &kd, fo});
    RenderOptions so = ropt;
    so.skip_origin = true;
    lanes.push_back({kSingleOriginLane, &kd, so});
    const absl::Time start = absl::Now();
    absl::StatusOr<std::unique_ptr<KdTreeBvhTracer>> bvh =
        KdTreeBvhTracer::Build(tree, choice.bvh_budget, "kdrt --memory_budget_gb");
    if (!bvh.ok()) return bvh.status();
    set.bvh = *std::move(bvh);
    set.bvh_built.build_s = absl::ToDoubleSeconds(absl::Now() - start);
    set.bvh_built.node_bytes = set.bvh->bvh().node_bytes();
    set.bvh_built.packet_bytes = set.bvh->bvh().packet_bytes();
    lanes.push_back({kSingleBvhLane, set.bvh.get(), so});
    lanes.push_back({kPacketsBvhLane, set.bvh.get(), fo});
  }
  if (choice.triangle_bvh) {
    if (!choice.fast) return absl::InvalidArgumentError("--triangle_bvh needs --fast_render");
    absl::StatusOr<std::unique_ptr<TriangleBvhTracer>> tri = TriangleBvhTracer::Build(soup);
    if (!tri.ok()) return tri.status();
    set.triangle_bvh = *std::move(tri);
    set.triangle_bvh_bytes = set.triangle_bvh->bvh()->bytes();
    set.triangle_bvh_build_s = set.triangle_bvh->build_seconds();
    RenderOptions so = ropt;
    so.skip_origin = true;
    lanes.push_back({kTriangleBvhLane, set.triangle_bvh.get(), so});
    lanes.push_back({kTriangleBvhPacketsLane, set.triangle_bvh.get(), fo});
  }
  const bool timed = choice.embree_timed && embree != nullptr;
  set.embree_lane = lanes.size();
  if (timed) lanes.push_back({kEmbreeLane, embree, ropt});
  RenderOptions embree_packets = ropt;
  embree_packets.packets = true;
  if (timed && choice.fast) lanes.push_back({kEmbreePacketsLane, embree, embree_packets});
  set.robust_lane = lanes.size();
  if (timed && choice.fast && choice.embree_robust) {
    EmbreeOptions ro = eo;
    ro.robust = true;
    absl::StatusOr<std::unique_ptr<EmbreeTracer>> e = EmbreeTracer::Create(soup, ro);
    if (!e.ok()) return e.status();
    set.robust = *std::move(e);
    lanes.push_back({kEmbreeRobustLane, set.robust.get(), ropt});
    lanes.push_back({kEmbreeRobustPacketsLane, set.robust.get(), embree_packets});
  }
  if (timed && choice.fast && ropt.threads == 1) {
    set.replay_single = std::make_unique<ReplayTracer>(kd);
    set.replay_packets = std::make_unique<ReplayTracer>(kd);
    lanes.push_back({kReplayLane, set.replay_single.get(), ropt});
    lanes.back().replay = set.replay_single.get();
    lanes.push_back({kReplayPacketsLane, set.replay_packets.get(), fo});
    lanes.back().replay = set.replay_packets.get();
  }
  return set;
}

}  // namespace kdtree
