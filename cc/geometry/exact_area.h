// Exact test for a triangle of zero area (repeated or collinear vertices).
//
// Each 2D orientation determinant of float coordinates is a sum of six
// products of two floats, every one exact in double; the sum is formed exactly
// as a nonoverlapping expansion (Shewchuk, "Adaptive Precision Floating-Point
// Arithmetic and Fast Robust Geometric Predicates", DCG 18(3), 1997: Two-Sum
// and Grow-Expansion), which is zero iff every component is zero. Needs IEEE
// double without FMA contraction or fast-math (.bazelrc).
#ifndef KDTREE_CC_GEOMETRY_EXACT_AREA_H_
#define KDTREE_CC_GEOMETRY_EXACT_AREA_H_

#include "cc/geometry/vec3.h"

namespace kdtree {

namespace exact_area_internal {

// s + e == a + b exactly.
inline void TwoSum(double a, double b, double* s, double* e) {
  *s = a + b;
  const double bv = *s - a;
  const double av = *s - bv;
  *e = (a - av) + (b - bv);
}

// True when ax by - ay bx + bx cy - by cx + cx ay - cy ax == 0 exactly.
inline bool Orient2dIsZero(float ax, float ay, float bx, float by, float cx, float cy) {
  const double p[6] = {double(ax) * by, -(double(ay) * bx), double(bx) * cy,
                       -(double(by) * cx), double(cx) * ay, -(double(cy) * ax)};
  double e[6];
  int n = 0;
  for (double q : p) {  // Grow-Expansion: add q to the expansion e[0..n)
    for (int i = 0; i < n; ++i) {
      double s, err;
      TwoSum(q, e[i], &s, &err);
      e[i] = err;
      q = s;
    }
    e[n++] = q;
  }
  for (int i = 0; i < n; ++i) {
    if (e[i] != 0) return false;
  }
  return true;
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
