#include "cc/render/kdtree_tracer.h"

#include <utility>

#include "absl/time/clock.h"
#include "absl/time/time.h"
#include "cc/kdtree/ray_packet.h"
#include "cc/kdtree/traversal.h"

namespace kdtree {

static_assert(kTracerPacket == kRayPacketSize, "renderer packets are the traversal's");

Hit KdTreeTracer::Intersect(const Ray& ray) const {
  return ::kdtree::Intersect(tree_, ray, options_);
}

// A ray that names its origin triangle is a secondary ray the renderer
// spawned from a surface (RenderOptions::skip_origin): that triangle is left
// untested, and the ray is searched from its end, the light for a shadow ray
// (TraversalOptions::origin_tri, from_end).
bool KdTreeTracer::Occluded(const Ray& ray, uint32_t origin_tri) const {
  if (origin_tri == kNoHit) return ::kdtree::Occluded(tree_, ray, options_);
  TraversalOptions o = options_;
  o.origin_tri = origin_tri;
  o.from_end = true;
  return ::kdtree::Occluded(tree_, ray, o);
}

void KdTreeTracer::IntersectPacket(const Ray* rays, int n, Hit* hits) const {
  ::kdtree::IntersectPacket(tree_, rays, n, hits, options_, closest_);
}

void KdTreeTracer::OccludedPacket(const Ray* rays, int n, const uint32_t* origin_tris,
                                  bool* occluded) const {
  TraversalOptions o = options_;
  o.from_end = o.from_end || origin_tris != nullptr;  // as Occluded's secondary rays
  ::kdtree::OccludedPacket(tree_, rays, n, origin_tris, occluded, o, any_);
}

absl::StatusOr<std::unique_ptr<KdTreeBvhTracer>> KdTreeBvhTracer::Build(
    const KdTree& tree, uint64_t max_packet_bytes, const std::string& how_to_raise) {
  absl::StatusOr<LeafBvh> bvh = BuildLeafBvh(tree, max_packet_bytes, how_to_raise);
  if (!bvh.ok()) return bvh.status();
  return std::make_unique<KdTreeBvhTracer>(tree, *std::move(bvh));
}

absl::StatusOr<std::unique_ptr<TriangleBvhTracer>> TriangleBvhTracer::Build(
    const TriangleSoup& soup) {
  const absl::Time start = absl::Now();
  absl::StatusOr<LeafBvh> bvh = BuildTriangleBvh(soup);
  if (!bvh.ok()) return bvh.status();
  auto tracer =
      std::make_unique<TriangleBvhTracer>(std::make_shared<const LeafBvh>(*std::move(bvh)));
  tracer->build_seconds_ = absl::ToDoubleSeconds(absl::Now() - start);
  return tracer;
}

}  // namespace kdtree
