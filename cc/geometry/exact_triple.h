// The sign of a triple product d . (p x q), right for every float input: a
// filter in double first, exact arithmetic when it cannot decide.
//
// Stage A of J. R. Shewchuk, "Adaptive Precision Floating-Point Arithmetic and
// Fast Robust Geometric Predicates", Discrete & Computational Geometry 18(3),
// 1997, section 4.3 (orient3d): the 3x3 determinant of differences of doubles,
// evaluated in double, has the sign of the exact one when its magnitude
// exceeds kErrBound times the permanent (the same expression with every
// product and sum taken in absolute value). Otherwise the exact expansions of
// expansion.h decide. Used by the watertight test's fallback (watertight.h),
// its exact t test (exact_t.h) and the renderer's exact verdicts
// (cc/render/exact_check.h). No overflow or underflow is assumed
// (|coordinates| between about 1e-30 and 1e30).
#ifndef KDTREE_CC_GEOMETRY_EXACT_TRIPLE_H_
#define KDTREE_CC_GEOMETRY_EXACT_TRIPLE_H_

#include "cc/geometry/vec3.h"

namespace kdtree {

// A vector of doubles: a difference of two float points (rounded only for
// extreme exponent ranges, which the filter's bound covers).
struct D3 {
  double x, y, z;
};
inline D3 Sub(const Vec3& p, const Vec3& q) {
  return {double(p.x) - q.x, double(p.y) - q.y, double(p.z) - q.z};
}

// Sign (-1, 0, 1) of u . (v x w) when its double evaluation decides it (0 only
// when every product is 0), else 2.
int FilteredTriple(const D3& u, const D3& v, const D3& w);

// Sign (-1, 0, 1) of d . ((p1 - p0) x (q1 - q0)), exactly.
int TripleSign(const Vec3& d, const Vec3& p1, const Vec3& p0, const Vec3& q1, const Vec3& q0);

}  // namespace kdtree

#endif  // KDTREE_CC_GEOMETRY_EXACT_TRIPLE_H_
