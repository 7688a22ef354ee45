#include "cc/kdtree/pruning.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace kdtree {
namespace {

template <typename T>
struct V3 {
  T x, y, z;
  T operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
};
template <typename T>
V3<T> Sub(const V3<T>& a, const V3<T>& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <typename T>
V3<T> CrossT(const V3<T>& a, const V3<T>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <typename T>
T DotT(const V3<T>& a, const V3<T>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}

// Separating-axis test of triangle (v0, v1, v2), already translated so that the
// box centre is the origin, against a box of half-size h.
template <typename T>
bool Overlap(const V3<T>& v0, const V3<T>& v1, const V3<T>& v2, const V3<T>& h) {
  // 1) The box normals: the triangle's bounds against the box.
  for (int k = 0; k < 3; ++k) {
    const T mn = std::min({v0[k], v1[k], v2[k]});
    const T mx = std::max({v0[k], v1[k], v2[k]});
    if (mn > h[k] || mx < -h[k]) return false;
  }
  // 2) The nine cross products of the box axes with the triangle edges.
  const V3<T> e[3] = {Sub(v1, v0), Sub(v2, v1), Sub(v0, v2)};
  const V3<T>* v[3] = {&v0, &v1, &v2};
  for (int i = 0; i < 3; ++i) {
    for (int k = 0; k < 3; ++k) {
      // axis = unit_k x e[i]
      V3<T> axis;
      if (k == 0) axis = {T(0), -e[i].z, e[i].y};
      if (k == 1) axis = {e[i].z, T(0), -e[i].x};
      if (k == 2) axis = {-e[i].y, e[i].x, T(0)};
      const T p0 = DotT(axis, *v[0]), p1 = DotT(axis, *v[1]), p2 = DotT(axis, *v[2]);
      const T mn = std::min({p0, p1, p2}), mx = std::max({p0, p1, p2});
      const T rad = h.x * std::abs(axis.x) + h.y * std::abs(axis.y) + h.z * std::abs(axis.z);
      if (mn > rad || mx < -rad) return false;
    }
  }
  // 3) The triangle's plane against the box: the three vertices projected
  // (the rounded normal is not exactly normal to the edges, so for a needle
  // triangle one vertex's projection could miss a box the others reach).
  const V3<T> n = CrossT(e[0], e[1]);
  const T d0 = DotT(n, v0), d1 = DotT(n, v1), d2 = DotT(n, v2);
  const T rad = h.x * std::abs(n.x) + h.y * std::abs(n.y) + h.z * std::abs(n.z);
  return !(std::min({d0, d1, d2}) > rad || std::max({d0, d1, d2}) < -rad);
}

template <typename T>
T MaxAbs(const V3<T>& v) {
  return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
}

// The test on coordinates relative to the box centre. With grow > 0 the box
// is grown by `grow` times the largest value the test compares (the box's
// half-size and the triangle's coordinates relative to the centre), plus the
// rounding of the centre itself: a bound on the test's own rounding, so the
// answer does not depend on where the scene sits (issue 24).
template <typename T>
bool Test(const Vec3& a, const Vec3& b, const Vec3& c, const AABB& box, T grow) {
  const V3<T> lo{T(box.lo.x), T(box.lo.y), T(box.lo.z)};
  const V3<T> hi{T(box.hi.x), T(box.hi.y), T(box.hi.z)};
  const V3<T> centre{(lo.x + hi.x) * T(0.5), (lo.y + hi.y) * T(0.5), (lo.z + hi.z) * T(0.5)};
  V3<T> h{(hi.x - lo.x) * T(0.5), (hi.y - lo.y) * T(0.5), (hi.z - lo.z) * T(0.5)};
  const V3<T> v0 = Sub(V3<T>{T(a.x), T(a.y), T(a.z)}, centre);
  const V3<T> v1 = Sub(V3<T>{T(b.x), T(b.y), T(b.z)}, centre);
  const V3<T> v2 = Sub(V3<T>{T(c.x), T(c.y), T(c.z)}, centre);
  if (grow > T(0)) {
    const T local = std::max({MaxAbs(h), MaxAbs(v0), MaxAbs(v1), MaxAbs(v2)});
    const T pad = local * grow + 4 * std::numeric_limits<T>::epsilon() * MaxAbs(centre);
    h = {h.x + pad, h.y + pad, h.z + pad};
  }
  return Overlap(v0, v1, v2, h);
}

}  // namespace

bool TriangleOverlapsBoxFloat(const Vec3& a, const Vec3& b, const Vec3& c, const AABB& box) {
  return Test<float>(a, b, c, box, 0.0f);
}

bool TriangleOverlapsBoxConservative(const Vec3& a, const Vec3& b, const Vec3& c,
                                     const AABB& box) {
  // A vertex in the (closed) box is a point of the triangle in the box: it overlaps,
  // exactly, and the separating-axis test (which never drops a triangle that
  // touches the box) would say so too. Most leaf references take this exit.
  if (box.Contains(a) || box.Contains(b) || box.Contains(c)) return true;
  return Test<double>(a, b, c, box, 1e-6);
}

}  // namespace kdtree
