// A packet of up to 16 rays as rows of floats (a structure of arrays), as
// ray-packet interfaces such as Embree's RTCRay16 take them.
#ifndef KDTREE_CC_GEOMETRY_RAY_ROWS_H_
#define KDTREE_CC_GEOMETRY_RAY_ROWS_H_

#include <cstdint>
#include <vector>

#include "cc/geometry/ray.h"

namespace kdtree {

// rows[k][i] = float k of rays[i] (origin x, y, z, dir x, y, z, tmin, tmax)
// for i < n <= 16, and 0 for n <= i < 16; each row 16 floats, 64-byte
// aligned. By ray_rows-inl.h's LoadRayRows, as the kd-tree's packets load
// their rays: a transposing load on targets of 16 float lanes, gathers
// elsewhere.
void RayRows(const Ray* rays, int n, float* const rows[8]);

// The Highway targets RayRows is compiled for that this CPU runs (its test
// runs each, through hwy::SetSupportedTargetsForTest).
std::vector<int64_t> RayRowsTargets();

}  // namespace kdtree

#endif  // KDTREE_CC_GEOMETRY_RAY_ROWS_H_
