// The one rule every tracer applies to an incoming ray before tracing it, so
// that the kd-tree and the brute-force reference see exactly the same ray.
#ifndef KDTREE_CC_GEOMETRY_RAY_CHECK_H_
#define KDTREE_CC_GEOMETRY_RAY_CHECK_H_

#include <cmath>
#include <limits>

#include "cc/geometry/ray.h"

namespace kdtree {

// Returns false when the ray hits nothing by definition: a NaN or infinite
// origin or direction component, a zero direction, a NaN tmin or tmax, or
// tmin > tmax. Such rays are misses, never a crash or a hang.
//
// Direction components of magnitude below FLT_MIN (denormals) are flushed to
// zero, keeping their sign. Their reciprocal overflows to infinity, so a
// traversal would treat the ray as parallel to a split plane it does cross
// (at t = (split - o) / d, which can be small when split - o is a denormal
// too); after flushing the ray truly is parallel, for every tracer alike.
inline bool SanitizeRay(Ray* ray) {
  if (!(ray->tmin <= ray->tmax)) return false;  // also catches NaN
  constexpr float kMinNormal = std::numeric_limits<float>::min();
  bool nonzero = false;
  for (int k = 0; k < 3; ++k) {
    const float o = ray->origin[k];
    float& d = ray->dir[k];
    if (!std::isfinite(o) || !std::isfinite(d)) return false;
    if (std::fabs(d) < kMinNormal) d = std::copysign(0.0f, d);
    nonzero = nonzero || d != 0.0f;
  }
  return nonzero;
}

}  // namespace kdtree

#endif  // KDTREE_CC_GEOMETRY_RAY_CHECK_H_
