// Secondary rays that never hit their own surface: the hit point with a
// rigorous bound on its rounding error, and ray origins offset just past it.
//
// Pharr, Jakob & Humphreys, "Physically Based Rendering: From Theory to
// Implementation", 3rd ed., 2016, sections 3.9.4-3.9.5 ("Bounding
// intersection point error", "Robust spawned ray origins"). The exact point q
// of the hit lies on the triangle's plane; the computed point p is within a
// box of half-widths `error` around q. The origin is moved along the normal by
// d = |n| . error (the box's extent along n), towards the side the new ray
// leaves through, then each moved coordinate is stepped one more float away,
// so the origin is strictly on that side of the exact plane. The watertight
// test rejects t below its own error bound (watertight.h), so a ray leaving
// the surface cannot re-hit it; the offset is a few ulps of the coordinates,
// not a fixed epsilon, so no real occluder farther than that is skipped, at
// any scale (1e-8 to 1e8 alike).
#ifndef KDTREE_CC_GEOMETRY_SPAWN_H_
#define KDTREE_CC_GEOMETRY_SPAWN_H_

#include "cc/geometry/ray.h"
#include "cc/geometry/vec3.h"

namespace kdtree {

// A computed point and the componentwise bound of its absolute error.
struct BoundedPoint {
  Vec3 p;
  Vec3 error;
};

// p = a + u (b - a) + v (c - a) in float. For any u, v the exact value of this
// expression lies on the plane of (a, b, c); rounding moves it by at most
// gamma(4) (|a| + |u (b - a)| + |v (c - a)|) per component (two roundings in
// each product term, two additions); the bound uses gamma(6) of the computed
// terms to cover their own rounding.
BoundedPoint HitPointWithError(const Vec3& a, const Vec3& b, const Vec3& c, float u, float v);

// Unit normal of (a, b, c), cross product evaluated in double (exact for
// float inputs up to rounding of the final normalisation). Zero for a
// degenerate triangle.
Vec3 GeometricNormal(const Vec3& a, const Vec3& b, const Vec3& c);

// The origin for a ray leaving the surface at `point` in direction `w`: moved
// along `n` (unit) to the side w points to (PBRT 3rd ed., OffsetRayOrigin).
Vec3 OffsetRayOrigin(const BoundedPoint& point, const Vec3& n, const Vec3& w);

// A ray from the surface in direction `dir`: tmin = 0, tmax = infinity.
Ray SpawnRay(const BoundedPoint& point, const Vec3& n, const Vec3& dir);

// A shadow ray from the surface to a point light: dir = light - origin,
// tmin = 0, tmax = 1 (the light itself; an occluder exactly there counts).
// Works on either side of the surface: the origin goes to the light's side.
Ray SpawnShadowRay(const BoundedPoint& point, const Vec3& n, const Vec3& light);

}  // namespace kdtree

#endif  // KDTREE_CC_GEOMETRY_SPAWN_H_
