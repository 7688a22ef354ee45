#include "cc/render/kdtree_tracer.h"

#include "cc/kdtree/ray_packet.h"
#include "cc/kdtree/traversal.h"

namespace kdtree {

static_assert(kTracerPacket == kRayPacketSize, "renderer packets are the traversal's");

Hit KdTreeTracer::Intersect(const Ray& ray) const {
  return ::kdtree::Intersect(tree_, ray, options_);
}

bool KdTreeTracer::Occluded(const Ray& ray, uint32_t origin_tri) const {
  if (origin_tri == kNoHit) return ::kdtree::Occluded(tree_, ray, options_);
  TraversalOptions o = options_;
  o.origin_tri = origin_tri;
  return ::kdtree::Occluded(tree_, ray, o);
}

void KdTreeTracer::IntersectPacket(const Ray* rays, int n, Hit* hits) const {
  ::kdtree::IntersectPacket(tree_, rays, n, hits, options_);
}

void KdTreeTracer::OccludedPacket(const Ray* rays, int n, const uint32_t* origin_tris,
                                  bool* occluded) const {
  ::kdtree::OccludedPacket(tree_, rays, n, origin_tris, occluded, options_);
}

}  // namespace kdtree
