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

// Conservative test (default): double arithmetic on coordinates relative to
// the box centre, the box grown by 1e-6 of the largest value compared (its
// half-size, the triangle's coordinates relative to the centre), so rounding
// can never drop a triangle that touches the box; at worst a triangle that
// misses by a hair is kept. The growth does not depend on where the scene
// sits: a scene moved far from the origin is pruned as at the origin.
bool TriangleOverlapsBoxConservative(const Vec3& a, const Vec3& b, const Vec3& c,
                                     const AABB& box);

}  // namespace kdtree

#endif  // KDTREE_CC_KDTREE_PRUNING_H_
