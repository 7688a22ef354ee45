#include "cc/bench/packet_counts.h"

#include <memory>
#include <utility>

#include "absl/strings/str_cat.h"
#include "cc/render/kdtree_tracer.h"

namespace kdtree {
namespace bench {
namespace {

double Quotient(uint64_t a, uint64_t b) {
  return b == 0 ? 0.0 : static_cast<double>(a) / static_cast<double>(b);
}

}  // namespace

Json PacketCountsJson(const PacketCounters& c) {
  const TraversalCounters& l = c.lanes;
  return Json{
      {"rays", l.rays},
      {"packets", c.packets},
      {"groups", c.groups},
      {"inner_steps", c.inner_steps},
      {"leaf_steps", c.leaf_steps},
      {"pushes", c.pushes},
      {"triangle_steps", c.triangle_steps},
      {"lane_inner_visits", l.inner_visits},
      {"lane_leaf_visits", l.leaf_visits},
      {"lane_triangle_tests", l.triangle_tests},
      {"per_packet",
       {{"groups", Quotient(c.groups, c.packets)},
        {"inner_steps", Quotient(c.inner_steps, c.packets)},
        {"leaf_steps", Quotient(c.leaf_steps, c.packets)},
        {"pushes", Quotient(c.pushes, c.packets)},
        {"triangle_steps", Quotient(c.triangle_steps, c.packets)}}},
      {"lanes_per_step",
       {{"inner", Quotient(l.inner_visits, c.inner_steps)},
        {"leaf", Quotient(l.leaf_visits, c.leaf_steps)},
        {"triangle", Quotient(l.triangle_tests, c.triangle_steps)}}},
      {"per_ray",
       {{"N_TR", Quotient(l.inner_visits, l.rays)}, {"N_IT", Quotient(l.triangle_tests, l.rays)}}}};
}

absl::StatusOr<Json> CountPackets(const TriangleSoup& soup, const KdTree& tree, const View& view,
                                  const RenderOptions& base, const RenderVariant& v,
                                  CountThrough through, std::shared_ptr<const LeafBvh> tri) {
  std::unique_ptr<ScopedPacketKernelTarget> target;
  if (!v.kernel.empty()) {
    target = std::make_unique<ScopedPacketKernelTarget>(v.kernel);
    if (!target->ok()) return absl::InvalidArgumentError(absl::StrCat("kernel target ", v.kernel));
  }
  PacketCounters closest, any;
  std::unique_ptr<Tracer> tracer;
  if (through == CountThrough::kTriangleBvh) {
    auto t = std::make_unique<TriangleBvhTracer>(std::move(tri));
    t->CountPackets(&closest, &any);
    tracer = std::move(t);
  } else if (through == CountThrough::kLeafBvh) {
    absl::StatusOr<std::unique_ptr<KdTreeBvhTracer>> t = KdTreeBvhTracer::Build(tree);
    if (!t.ok()) return t.status();
    (*t)->CountPackets(&closest, &any);
    tracer = *std::move(t);
  } else {
    auto t = std::make_unique<KdTreeTracer>(tree);
    t->CountPackets(&closest, &any);
    tracer = std::move(t);
  }
  RenderOptions o = base;
  o.threads = 1;
  o.packets = true;
  o.skip_origin = v.skip_origin;
  Render(soup, *tracer, view, o);
  return Json{{"kernel", PacketKernelTarget()},
              {"closest", PacketCountsJson(closest)},
              {"any", PacketCountsJson(any)}};
}

}  // namespace bench
}  // namespace kdtree
