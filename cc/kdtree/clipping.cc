#include "cc/kdtree/clipping.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "cc/geometry/float_bits.h"

namespace kdtree {
namespace {

struct DVec {
  double v[3];
};

DVec ToD(const Vec3& p) { return {{p.x, p.y, p.z}}; }

// Point of segment p-q at coordinate `pos` on `axis` (p and q on opposite sides).
template <typename T, typename V>
V Cut(const V& p, const V& q, int axis, T pos) {
  V r;
  const T t = (pos - p.v[axis]) / (q.v[axis] - p.v[axis]);
  for (int k = 0; k < 3; ++k) r.v[k] = p.v[k] + (q.v[k] - p.v[k]) * t;
  r.v[axis] = pos;  // exactly on the plane
  return r;
}

struct FVec {
  float v[3];
};
FVec ToF(const Vec3& p) { return {{p.x, p.y, p.z}}; }

// Box of the cut points (up to two); double points are rounded outward to float.
template <typename V>
AABB BoxOf(const V* pts, int count, bool outward) {
  AABB box;
  for (int i = 0; i < count; ++i) {
    for (int k = 0; k < 3; ++k) {
      float lo = static_cast<float>(pts[i].v[k]);
      float hi = lo;
      if (outward) {
        if (static_cast<double>(lo) > pts[i].v[k]) lo = NextFloatDown(lo);
        if (static_cast<double>(hi) < pts[i].v[k]) hi = NextFloatUp(hi);
      }
      box.lo[k] = std::min(box.lo[k], lo);
      box.hi[k] = std::max(box.hi[k], hi);
    }
  }
  return box;
}

// Box of the float vertices (exact: no rounding).
AABB BoxOfVertices(const Vec3* const* pts, int count) {
  AABB box;
  for (int i = 0; i < count; ++i) box.Extend(*pts[i]);
  return box;
}

// Each side's box is the box of its vertices of the triangle and of the cut
// points, which both sides share: the cut points are computed and rounded
// once (min and max do not depend on the order of the points), and the
// triangle's own vertices, floats already, need no rounding. `sorted` and
// `verts` are the same three vertices by coordinate on `axis`.
template <typename T, typename V>
ClipCase ClipImpl(const V* sorted, const Vec3* const* verts, ClipCase kind, int axis, T pos,
                  bool outward, const AABB& ref_box, AABB* left, AABB* right) {
  const V& lo = sorted[0];
  const V& mid = sorted[1];
  const V& hi = sorted[2];
  V cut[2];
  int ncut = 0;
  AABB lbox, rbox;  // the triangle's vertices on each side
  switch (kind) {
    case ClipCase::kMiddleOnPlane: {
      cut[ncut++] = Cut<T>(lo, hi, axis, pos);
      lbox = BoxOfVertices(verts, 2);
      rbox = BoxOfVertices(verts + 1, 2);
      break;
    }
    case ClipCase::kLowAlone: {
      cut[ncut++] = Cut<T>(lo, mid, axis, pos);
      cut[ncut++] = Cut<T>(lo, hi, axis, pos);
      lbox = BoxOfVertices(verts, 1);
      rbox = BoxOfVertices(verts + 1, 2);
      break;
    }
    case ClipCase::kHighAlone: {
      cut[ncut++] = Cut<T>(lo, hi, axis, pos);
      cut[ncut++] = Cut<T>(mid, hi, axis, pos);
      lbox = BoxOfVertices(verts, 2);
      rbox = BoxOfVertices(verts + 2, 1);
      break;
    }
    case ClipCase::kNotStraddling:
      return kind;
  }
  const AABB cuts = BoxOf(cut, ncut, outward);
  lbox.Extend(cuts);
  rbox.Extend(cuts);
  *left = Intersect(lbox, ref_box);
  *right = Intersect(rbox, ref_box);
  // The cut side of each box lies exactly on the plane.
  left->hi[axis] = std::min(left->hi[axis], static_cast<float>(pos));
  right->lo[axis] = std::max(right->lo[axis], static_cast<float>(pos));
  return kind;
}

int Sign(float x, float pos) { return x < pos ? -1 : (x > pos ? 1 : 0); }

}  // namespace

ClipCase ClassifyTriangle(const Vec3& a, const Vec3& b, const Vec3& c, int axis, float pos) {
  // The sorted signs are (-1, s, 1) when the triangle straddles: s is told by
  // how many vertices lie below and above the plane.
  const int sa = Sign(a[axis], pos), sb = Sign(b[axis], pos), sc = Sign(c[axis], pos);
  const int below = (sa < 0) + (sb < 0) + (sc < 0), above = (sa > 0) + (sb > 0) + (sc > 0);
  if (below == 0 || above == 0) return ClipCase::kNotStraddling;
  if (below + above == 2) return ClipCase::kMiddleOnPlane;
  return below == 1 ? ClipCase::kLowAlone : ClipCase::kHighAlone;
}

ClipCase ClipTriangle(const Vec3& a, const Vec3& b, const Vec3& c, int axis, float pos,
                      const AABB& ref_box, bool conservative, AABB* left, AABB* right) {
  const ClipCase kind = ClassifyTriangle(a, b, c, axis, pos);
  if (kind == ClipCase::kNotStraddling) return kind;
  // Vertices by coordinate on `axis` (three compare-exchanges). The order of
  // equal coordinates does not matter: a tie is possible only between the
  // two vertices on one side, and each case below treats those two alike.
  const Vec3* v[3] = {&a, &b, &c};
  const auto order = [axis](const Vec3*& p, const Vec3*& q) {
    if ((*q)[axis] < (*p)[axis]) std::swap(p, q);
  };
  order(v[0], v[1]);
  order(v[1], v[2]);
  order(v[0], v[1]);
  if (conservative) {
    const DVec sorted[3] = {ToD(*v[0]), ToD(*v[1]), ToD(*v[2])};
    return ClipImpl<double>(sorted, v, kind, axis, static_cast<double>(pos), true, ref_box, left,
                            right);
  }
  const FVec sorted[3] = {ToF(*v[0]), ToF(*v[1]), ToF(*v[2])};
  return ClipImpl<float>(sorted, v, kind, axis, pos, false, ref_box, left, right);
}

}  // namespace kdtree
