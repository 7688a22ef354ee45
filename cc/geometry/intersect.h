// Ray-triangle intersection.
//
// Moeller & Trumbore, "Fast, minimum storage ray-triangle intersection",
// Journal of Graphics Tools 2(1), 1997. The kd-tree and the brute-force
// reference call this same function, so their answers can be compared exactly.
// This is the fast mode (IntersectionMode::kFast); it can miss a ray through an
// edge shared by two triangles. The default is the watertight test of
// watertight.h.
#ifndef KDTREE_CC_GEOMETRY_INTERSECT_H_
#define KDTREE_CC_GEOMETRY_INTERSECT_H_

#include "cc/geometry/ray.h"
#include "cc/geometry/vec3.h"

namespace kdtree {

// Precomputed form of a triangle for intersection: one vertex and two edges.
struct TriAccel {
  Vec3 v0, e1, e2;
};

inline TriAccel MakeTriAccel(const Vec3& a, const Vec3& b, const Vec3& c) {
  return {a, b - a, c - a};
}

// Returns true and sets *t, *u, *v when the ray hits the triangle with
// tmin < t <= tmax (inclusive so that ties
// at equal t can be broken by triangle index, see Closer()). Edges and vertices are inclusive (u, v >= 0, u + v <= 1).
inline bool IntersectTriangle(const Ray& ray, const TriAccel& tri, float tmin, float tmax,
                              float* t, float* u, float* v) {
  const Vec3 p = Cross(ray.dir, tri.e2);
  const float det = Dot(tri.e1, p);
  if (det == 0.0f || !(det == det)) return false;  // parallel, degenerate or NaN
  const float inv_det = 1.0f / det;
  const Vec3 s = ray.origin - tri.v0;
  const float uu = Dot(s, p) * inv_det;
  if (!(uu >= 0.0f && uu <= 1.0f)) return false;
  const Vec3 q = Cross(s, tri.e1);
  const float vv = Dot(ray.dir, q) * inv_det;
  if (!(vv >= 0.0f && uu + vv <= 1.0f)) return false;
  const float tt = Dot(tri.e2, q) * inv_det;
  if (!(tt > tmin && tt <= tmax)) return false;
  *t = tt;
  *u = uu;
  *v = vv;
  return true;
}

}  // namespace kdtree

#endif  // KDTREE_CC_GEOMETRY_INTERSECT_H_
