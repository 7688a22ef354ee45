// What the packet kernels do in a render: render_bench's record
// packet_counts, one untimed render per packet variant, through the kd-tree
// (kd_packet, kd_packet_origin), the BVH over its leaves (kd_bvh_packet) or
// the BVH over whole triangles (tri_bvh_packet).
// Per query (closest hit: primary rays; any hit: shadow and AO rays), the
// counters of cc/kdtree/ray_packet.h and what they mean per packet: the
// kernel's steps (inner nodes, leaves, vector triangle tests) and how many
// lanes each step carries, and per ray N_TR and N_IT: through the kd-tree,
// the single-ray statistics, which each lane reproduces; through the BVH,
// its nodes and the triangle tests per lane.
#ifndef KDTREE_CC_BENCH_PACKET_COUNTS_H_
#define KDTREE_CC_BENCH_PACKET_COUNTS_H_

#include <memory>

#include "absl/status/statusor.h"
#include "cc/bench/bench_record.h"
#include "cc/bench/render_check.h"
#include "cc/geometry/triangle.h"
#include "cc/kdtree/ray_packet.h"
#include "cc/kdtree/tree.h"
#include "cc/kdtree/triangle_bvh.h"
#include "cc/render/renderer.h"
#include "cc/render/view.h"

namespace kdtree {
namespace bench {

// The counters and their per-packet and per-ray quotients.
Json PacketCountsJson(const PacketCounters& c);

// What the packets go through.
enum class CountThrough {
  kKdTree,       // the kd-tree (kd_packet, kd_packet_origin)
  kLeafBvh,      // the BVH over its leaves (kd_bvh_packet; leaf_bvh.h)
  kTriangleBvh,  // the BVH over whole triangles (tri_bvh_packet; triangle_bvh.h)
};

// One render with one thread and v's modes (v.packets must be set;
// v.kernel: the packet kernel's target, as timed), the packets through
// `through`: `tree`, the BVH over its leaves (built again for the count, in
// milliseconds) or `tri` (the timed tracer's, not null then); a BVH's inner
// steps are its nodes: {"kernel", "closest", "any"}. Error: a kernel target
// this machine cannot run.
absl::StatusOr<Json> CountPackets(const TriangleSoup& soup, const KdTree& tree, const View& view,
                                  const RenderOptions& base, const RenderVariant& v,
                                  CountThrough through = CountThrough::kKdTree,
                                  std::shared_ptr<const LeafBvh> tri = nullptr);

}  // namespace bench
}  // namespace kdtree

#endif  // KDTREE_CC_BENCH_PACKET_COUNTS_H_
