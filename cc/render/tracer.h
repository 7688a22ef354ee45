// The two queries a renderer needs from any ray tracer (the kd-tree, brute
// force, Embree), so that every tracer is driven by the very same rays.
#ifndef KDTREE_CC_RENDER_TRACER_H_
#define KDTREE_CC_RENDER_TRACER_H_

#include <cstdint>
#include <string>

#include "cc/geometry/ray.h"

namespace kdtree {

inline constexpr int kTracerPacket = 16;

class Tracer {
 public:
  virtual ~Tracer() = default;
  // Short name for reports ("kdtree", "brute_force", "embree").
  virtual std::string name() const = 0;
  // Closest hit with ray.tmin < t <= ray.tmax: triangle index into the soup
  // the tracer was built on, t, and barycentrics u, v (hit point = (1 - u - v)
  // a + u b + v c). Hit::tri is kNoHit on a miss. Must be safe to call from
  // several threads at once.
  virtual Hit Intersect(const Ray& ray) const = 0;
  // True when some triangle is hit with ray.tmin < t <= ray.tmax.
  // `origin_tri`: the triangle the ray was spawned from (cc/geometry/
  // spawn.h), or kNoHit; a tracer may leave it untested when it can never
  // hit it (the kd-tree's watertight test: TraversalOptions::origin_tri),
  // and the answer must be the same either way.
  virtual bool Occluded(const Ray& ray, uint32_t origin_tri) const = 0;
  bool Occluded(const Ray& ray) const { return Occluded(ray, kNoHit); }

  // The same queries for a packet of n <= kTracerPacket rays (the renderer's
  // 4x4 pixel blocks, RenderOptions::packets); origin_tris may be null (no
  // ray has one). Each result must be what the single-ray query gives for
  // that ray. Default: one ray at a time.
  virtual void IntersectPacket(const Ray* rays, int n, Hit* hits) const {
    for (int i = 0; i < n; ++i) hits[i] = Intersect(rays[i]);
  }
  virtual void OccludedPacket(const Ray* rays, int n, const uint32_t* origin_tris,
                              bool* occluded) const {
    for (int i = 0; i < n; ++i) occluded[i] = Occluded(rays[i], origin_tris ? origin_tris[i] : kNoHit);
  }
};

}  // namespace kdtree

#endif  // KDTREE_CC_RENDER_TRACER_H_
