// Pruning: triangles whose surface does not overlap a box are dropped.
//
// The report, section "Pruning": during the build, clipped boxes that miss
// their child's box are dropped (see builder.cc); when a leaf is created, every
// reference is tested with the separating-axis triangle-box test of
// T. Akenine-Moeller, "Fast 3D triangle-box overlap testing", Journal of
// Graphics Tools 6(1), 2001 (the report's [4]): 13 axes (3 box normals, the
// triangle normal, 9 edge cross products). Touching counts as overlap.
#ifndef KDTREE_CC_KDTREE_PRUNING_H_
#define KDTREE_CC_KDTREE_PRUNING_H_

#include "cc/geometry/aabb.h"
#include "cc/geometry/vec3.h"

namespace kdtree {

// Exact-as-float test (seed-compatible mode): float arithmetic, box as given.
bool TriangleOverlapsBoxFloat(const Vec3& a, const Vec3& b, const Vec3& c, const AABB& box);

// Conservative test (default): double arithmetic and the box grown by a
// relative 1e-6 of its size, so rounding can never drop a triangle that
// touches the box; at worst a triangle that misses by a hair is kept.
bool TriangleOverlapsBoxConservative(const Vec3& a, const Vec3& b, const Vec3& c,
                                     const AABB& box);

}  // namespace kdtree

#endif  // KDTREE_CC_KDTREE_PRUNING_H_
