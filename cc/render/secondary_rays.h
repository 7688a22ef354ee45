// Secondary rays from a primary hit: the offset origin, shadow rays to point
// lights, and cosine-distributed ambient-occlusion rays.
//
// Origin offset (self-intersection avoidance): the error-bound spawn of
// cc/geometry/spawn.h (Pharr, Jakob & Humphreys, "Physically Based Rendering",
// 3rd ed., 2016, sections 3.9.4-3.9.5). The hit point is recomputed from the
// triangle and the barycentrics, p = a + u (b - a) + v (c - a), together with
// a rigorous componentwise bound on its rounding error (HitPointWithError); a
// secondary ray starts at p moved along the unit geometric normal by the
// extent of that error box along the normal, then one more float away, to the
// side the ray leaves through (OffsetRayOrigin). The origin is then strictly on
// that side of the triangle's exact plane, and the watertight test rejects t
// below its own error bound, so a ray leaving the surface never re-hits it.
// The offset is a few ulps of the coordinates, not a fixed epsilon: no real
// occluder farther than that is skipped, at any scale.
//
// Shadow ray (SpawnShadowRay): origin offset towards the light's side of the
// surface, dir = light - origin (not normalised), tmin = 0, tmax = 1 (the
// light itself). A light on the far side of the surface (as seen from the
// camera) thus gets a ray that leaves through the back: its own triangle never
// blocks it, and the shading gives that light zero anyway (the cosine with the
// camera-facing normal is negative).
//
// Ambient occlusion ray (SpawnRay): unit direction drawn from the
// cosine-weighted hemisphere around the camera-facing normal (Malley's method:
// uniform disk sample lifted to the hemisphere; PBRT 3rd ed. 13.6.3), origin
// offset to that side, tmax = the view's AO distance. The two uniforms come
// from a counter-based hash of (pixel, sample), so the rays are the same
// whatever the thread count or the order of evaluation.
#ifndef KDTREE_CC_RENDER_SECONDARY_RAYS_H_
#define KDTREE_CC_RENDER_SECONDARY_RAYS_H_

#include <cstdint>

#include "cc/geometry/ray.h"
#include "cc/geometry/spawn.h"
#include "cc/geometry/triangle.h"
#include "cc/geometry/vec3.h"

namespace kdtree {

struct SurfacePoint {
  BoundedPoint point;  // hit point from barycentrics, with its error bound
  Vec3 normal;         // unit geometric normal, facing the incoming ray
  const Vec3& p() const { return point.p; }
};

// `hit` must be a hit of `ray` on `soup`.
SurfacePoint MakeSurfacePoint(const TriangleSoup& soup, const Ray& ray, const Hit& hit);

// Shadow ray from `sp` to a point light (see above).
Ray ShadowRay(const SurfacePoint& sp, const Vec3& light);

Ray AoRay(const SurfacePoint& sp, uint32_t pixel, int sample, float distance);

// Two uniforms in [0, 1) from (pixel, sample): SplitMix64 finalizer (Steele,
// Lea, Flood, "Fast splittable pseudorandom number generators", OOPSLA 2014).
void HashUniforms(uint32_t pixel, uint32_t sample, float* r1, float* r2);

}  // namespace kdtree

#endif  // KDTREE_CC_RENDER_SECONDARY_RAYS_H_
