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

// Box of up to four points; double points are rounded outward to float.
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

template <typename T, typename V>
ClipCase ClipImpl(const V* sorted, ClipCase kind, int axis, T pos, bool outward,
                  const AABB& ref_box, AABB* left, AABB* right) {
  const V& lo = sorted[0];
  const V& mid = sorted[1];
  const V& hi = sorted[2];
  V l[4], r[4];
  int nl = 0, nr = 0;
  switch (kind) {
    case ClipCase::kMiddleOnPlane: {
      const V i = Cut<T>(lo, hi, axis, pos);
      l[nl++] = lo, l[nl++] = mid, l[nl++] = i;
      r[nr++] = hi, r[nr++] = mid, r[nr++] = i;
      break;
    }
    case ClipCase::kLowAlone: {
      const V i1 = Cut<T>(lo, mid, axis, pos), i2 = Cut<T>(lo, hi, axis, pos);
      l[nl++] = lo, l[nl++] = i1, l[nl++] = i2;
      r[nr++] = mid, r[nr++] = hi, r[nr++] = i1, r[nr++] = i2;
      break;
    }
    case ClipCase::kHighAlone: {
      const V i1 = Cut<T>(lo, hi, axis, pos), i2 = Cut<T>(mid, hi, axis, pos);
      l[nl++] = lo, l[nl++] = mid, l[nl++] = i1, l[nl++] = i2;
      r[nr++] = hi, r[nr++] = i1, r[nr++] = i2;
      break;
    }
    case ClipCase::kNotStraddling:
      return kind;
  }
  *left = Intersect(BoxOf(l, nl, outward), ref_box);
  *right = Intersect(BoxOf(r, nr, outward), ref_box);
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
    return ClipImpl<double>(sorted, kind, axis, static_cast<double>(pos), true, ref_box, left,
                            right);
  }
  const FVec sorted[3] = {ToF(*v[0]), ToF(*v[1]), ToF(*v[2])};
  return ClipImpl<float>(sorted, kind, axis, pos, false, ref_box, left, right);
}

}  // namespace kdtree
