// Exact test for a triangle of zero area (repeated or collinear vertices).
//
// Each 2D orientation determinant of float coordinates is a sum of six
// products of two floats, every one exact in double; its sign is taken exactly
// (expansion.h: Shewchuk, "Adaptive Precision Floating-Point Arithmetic and
// Fast Robust Geometric Predicates", DCG 18(3), 1997). Needs IEEE double
// without FMA contraction or fast-math (.bazelrc). The loader drops such
// triangles with it (cc/io: IsDegenerateTriangle).
#ifndef KDTREE_CC_GEOMETRY_EXACT_AREA_H_
#define KDTREE_CC_GEOMETRY_EXACT_AREA_H_

#include <cmath>

#include "cc/geometry/expansion.h"
#include "cc/geometry/vec3.h"

namespace kdtree {

namespace exact_area_internal {

// True when ax by - ay bx + bx cy - by cx + cx ay - cy ax == 0 exactly. The
// orient2d filter (Shewchuk 1997, section 4.3, stage A) settles almost every
// case; the rest are summed as an expansion.
inline bool Orient2dIsZero(float ax, float ay, float bx, float by, float cx, float cy) {
  constexpr double kEps = 1.1102230246251565e-16;  // 2^-53
  constexpr double kErrBound = (3.0 + 16.0 * kEps) * kEps;
  const double left = (double(ax) - cx) * (double(by) - cy);
  const double right = (double(ay) - cy) * (double(bx) - cx);
  if (std::fabs(left - right) > kErrBound * (std::fabs(left) + std::fabs(right))) return false;
  const expansion::Terms p = {double(ax) * by, -(double(ay) * bx), double(bx) * cy,
                              -(double(by) * cx), double(cx) * ay, -(double(cy) * ax)};
  return expansion::Sign(p) == 0;
}

}  // namespace exact_area_internal

// True when (b - a) x (c - a) is exactly the zero vector.
inline bool HasZeroArea(const Vec3& a, const Vec3& b, const Vec3& c) {
  using exact_area_internal::Orient2dIsZero;
  return Orient2dIsZero(a.x, a.y, b.x, b.y, c.x, c.y) &&
         Orient2dIsZero(a.y, a.z, b.y, b.z, c.y, c.z) &&
         Orient2dIsZero(a.z, a.x, b.z, b.x, c.z, c.x);
}

}  // namespace kdtree

#endif  // KDTREE_CC_GEOMETRY_EXACT_AREA_H_
