// The two queries a renderer needs from any ray tracer (the kd-tree, brute
// force, Embree), so that every tracer is driven by the very same rays.
#ifndef KDTREE_CC_RENDER_TRACER_H_
#define KDTREE_CC_RENDER_TRACER_H_

#include <string>

#include "cc/geometry/ray.h"

namespace kdtree {

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
  virtual bool Occluded(const Ray& ray) const = 0;
};

}  // namespace kdtree

#endif  // KDTREE_CC_RENDER_TRACER_H_
