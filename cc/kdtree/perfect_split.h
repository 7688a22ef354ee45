// Perfect splits: the exact box of the part of a triangle inside a box.
//
// V. Havran, "Heuristic Ray Shooting Algorithms", PhD thesis, Czech Technical
// University, 2000, section 4.x ("split clipping"); Wald & Havran, "On
// building fast kd-trees for ray tracing, and on doing that in O(N log N)",
// IEEE RT 2006, section 4.1 ("perfect splits"). The triangle is clipped as a
// polygon against the six planes of the box with the Sutherland-Hodgman
// algorithm (I. E. Sutherland and G. W. Hodgman, "Reentrant polygon clipping",
// CACM 17(1), 1974), and the result's bounding box replaces the reference's
// box. The report's clipping (clipping.h) cuts the triangle at the one split
// plane and intersects with the old box, which can leave the box much larger
// than the triangle's part.
//
// Conservative: the polygon is clipped in double against the box grown by
// 1e-6 of the box's extent plus the rounding of the cut
// points at the coordinates' magnitude (independent of where the scene sits,
// like the conservative pruning test, pruning.h), its box is rounded outward
// to float and then intersected with the exact box, so a triangle that
// touches the box is never lost.
#ifndef KDTREE_CC_KDTREE_PERFECT_SPLIT_H_
#define KDTREE_CC_KDTREE_PERFECT_SPLIT_H_

#include "cc/geometry/aabb.h"
#include "cc/geometry/vec3.h"

namespace kdtree {

// The box of triangle (a, b, c) clipped to `box`, in *out. False when the
// triangle's part in the box is empty (it misses the box), *out untouched.
bool ClipTriangleToBox(const Vec3& a, const Vec3& b, const Vec3& c, const AABB& box, AABB* out);

}  // namespace kdtree

#endif  // KDTREE_CC_KDTREE_PERFECT_SPLIT_H_
