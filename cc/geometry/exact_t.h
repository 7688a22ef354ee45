// Whether the hit of a ray with a triangle's plane lies beyond tmin, decided
// exactly (expansion.h, Shewchuk 1997), for the hits whose t is too close to
// tmin for its rounding bound to decide (watertight.h).
//
// With A = a - o, B = b - o, C = c - o (o the ray origin, d its direction),
// det = d . ((b - a) x (c - a)) = d . (B x C) + d . (C x A) + d . (A x B) and
// the plane is hit at t = A . (B x C) / det; t > tmin exactly when
// (A . (B x C) - tmin det) has the sign of det (and det is not zero). For
// tmin = 0 both signs are first taken in double, certified by Shewchuk's
// orient3d error bound; only when that cannot decide are the expansions
// formed (heap-allocated, slow).
#ifndef KDTREE_CC_GEOMETRY_EXACT_T_H_
#define KDTREE_CC_GEOMETRY_EXACT_T_H_

#include "cc/geometry/vec3.h"

namespace kdtree {

// True when the line o + t d meets the plane of (a, b, c) at a t > tmin,
// exactly; false when it does not or the line is parallel to the plane.
bool ExactPlaneHitBeyond(const Vec3& o, const Vec3& d, const Vec3& a, const Vec3& b,
                         const Vec3& c, float tmin);

namespace exact_t_internal {
// The same decision in expansions only (no double filter), for tests.
bool ExactExpansions(const Vec3& o, const Vec3& d, const Vec3& a, const Vec3& b, const Vec3& c,
                     float tmin);
}  // namespace exact_t_internal

}  // namespace kdtree

#endif  // KDTREE_CC_GEOMETRY_EXACT_T_H_
