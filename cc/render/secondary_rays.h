// Secondary rays from a primary hit: the offset origin, shadow rays to point
// lights, and cosine-distributed ambient-occlusion rays.
//
// Origin offset (self-intersection avoidance). The hit point is recomputed
// from the triangle and the barycentrics, p = a + u (b - a) + v (c - a); in
// float its absolute error is below about 9 * 2^-24 * m ~ 5.4e-7 m, with m the
// largest vertex coordinate magnitude (max over a, b, c of |x|, |y|, |z|), and
// the Moeller-Trumbore distance to the triangle's own plane from such a point
// errs by the same order. The origin is therefore moved along the unit
// geometric normal by
//   eps = 1e-5 * m        (about 20 times that bound; scale-invariant, so
//                          tiny and huge scenes behave alike)
// towards the side the primary ray came from (the normal is flipped to face
// it; two-sided surfaces), and secondary rays start at tmin = 0. (The same idea
// as Pharr, Jakob, Humphreys, "Physically Based Rendering", 3rd ed., 3.9.5,
// "Robust spawned ray origins", with a fixed multiple of the bound.)
//
// Shadow ray: towards the light from the offset origin, unit direction,
// tmax = distance * (1 - 1e-5) so nothing at or behind the light counts.
// A light on the far side of the surface is behind the triangle itself, so
// the ray hits that triangle: the point is in shadow, as it should be.
//
// Ambient occlusion ray: unit direction drawn from the cosine-weighted
// hemisphere around the facing normal (Malley's method: uniform disk sample
// lifted to the hemisphere; PBRT 3rd ed. 13.6.3), tmax = the view's AO distance.
// The two uniforms come from a counter-based hash of (pixel, sample), so the
// rays are the same whatever the thread count or the order of evaluation.
#ifndef KDTREE_CC_RENDER_SECONDARY_RAYS_H_
#define KDTREE_CC_RENDER_SECONDARY_RAYS_H_

#include <cstdint>

#include "cc/geometry/ray.h"
#include "cc/geometry/triangle.h"
#include "cc/geometry/vec3.h"

namespace kdtree {

struct SurfacePoint {
  Vec3 p;        // hit point from barycentrics
  Vec3 normal;   // unit geometric normal, facing the incoming ray
  float eps;     // offset distance (see above)
  Vec3 origin;   // p + eps * normal: where secondary rays start
};

// `hit` must be a hit of `ray` on `soup`.
SurfacePoint MakeSurfacePoint(const TriangleSoup& soup, const Ray& ray, const Hit& hit);

inline constexpr float kOffsetScale = 1e-5f;
inline constexpr float kShadowTmaxShrink = 1e-5f;

Ray ShadowRay(const SurfacePoint& sp, const Vec3& light);

Ray AoRay(const SurfacePoint& sp, uint32_t pixel, int sample, float distance);

// Two uniforms in [0, 1) from (pixel, sample): SplitMix64 finalizer (Steele,
// Lea, Flood, "Fast splittable pseudorandom number generators", OOPSLA 2014).
void HashUniforms(uint32_t pixel, uint32_t sample, float* r1, float* r2);

}  // namespace kdtree

#endif  // KDTREE_CC_RENDER_SECONDARY_RAYS_H_
