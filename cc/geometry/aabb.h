// Axis-aligned bounding box: surface area, split at a plane, overlap.
#ifndef KDTREE_CC_GEOMETRY_AABB_H_
#define KDTREE_CC_GEOMETRY_AABB_H_

#include <limits>

#include "cc/geometry/vec3.h"

namespace kdtree {

struct AABB {
  Vec3 lo{std::numeric_limits<float>::infinity(), std::numeric_limits<float>::infinity(),
          std::numeric_limits<float>::infinity()};
  Vec3 hi{-std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
          -std::numeric_limits<float>::infinity()};

  AABB() = default;
  AABB(const Vec3& l, const Vec3& h) : lo(l), hi(h) {}

  // A box that contains nothing (the identity of Extend).
  static AABB Empty() { return AABB(); }

  // True when lo <= hi on every axis (a point or a flat box is valid).
  bool Valid() const { return lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z; }

  void Extend(const Vec3& p) {
    lo = Min(lo, p);
    hi = Max(hi, p);
  }
  void Extend(const AABB& b) {
    lo = Min(lo, b.lo);
    hi = Max(hi, b.hi);
  }

  Vec3 Extent() const { return hi - lo; }

  // Axis of largest extent; ties go to the lower axis (x before y before z).
  int LongestAxis() const {
    const Vec3 e = Extent();
    int axis = 0;
    if (e.y > e[axis]) axis = 1;
    if (e.z > e[axis]) axis = 2;
    return axis;
  }

  // 2 (dx dy + dy dz + dz dx), evaluated in this exact order (the
  // seed-compatible binning depends on the float rounding of this sum).
  float SurfaceArea() const {
    const Vec3 e = Extent();
    return 2.0f * (e.x * e.y + e.y * e.z + e.z * e.x);
  }

  // Closed-interval overlap: boxes that only touch do overlap.
  bool Overlaps(const AABB& b) const {
    return lo.x <= b.hi.x && b.lo.x <= hi.x && lo.y <= b.hi.y && b.lo.y <= hi.y &&
           lo.z <= b.hi.z && b.lo.z <= hi.z;
  }

  bool Contains(const Vec3& p) const {
    return lo.x <= p.x && p.x <= hi.x && lo.y <= p.y && p.y <= hi.y && lo.z <= p.z &&
           p.z <= hi.z;
  }

  // The part of this box on one side of the plane `axis = pos`.
  AABB LeftOf(int axis, float pos) const {
    AABB b = *this;
    b.hi[axis] = pos;
    return b;
  }
  AABB RightOf(int axis, float pos) const {
    AABB b = *this;
    b.lo[axis] = pos;
    return b;
  }
};

// The six bounds as one array: lo.x lo.y lo.z hi.x hi.y hi.z, so that an
// axis is an index instead of a select (hot loops of the builders).
static_assert(sizeof(AABB) == 6 * sizeof(float), "box is lo.xyz, hi.xyz");
inline const float* Coords(const AABB& b) { return &b.lo.x; }

// Intersection of two boxes; not Valid() when they are disjoint.
inline AABB Intersect(const AABB& a, const AABB& b) { return AABB(Max(a.lo, b.lo), Min(a.hi, b.hi)); }

}  // namespace kdtree

#endif  // KDTREE_CC_GEOMETRY_AABB_H_
