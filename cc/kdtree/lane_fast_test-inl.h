// The fast triangle test (Moeller & Trumbore, "Fast, minimum storage
// ray-triangle intersection", JGT 2(1), 1997; cc/geometry/intersect.h
// IntersectTriangle) for one ray against a vector of triangles, a triangle
// per lane: the single-ray traversal's leaf step in the fast mode, on the
// leaf packets the watertight mode reads (leaf_layout.h), so that the two
// tests are timed on the same layout and the same step.
//
// Each lane runs IntersectTriangle's float operations in its order (Cross
// and Dot as vec3.h writes them; the build has no FMA contraction:
// -ffp-contract=off), with the edges e1 = b - a and e2 = c - a formed as
// MakeTriAccel forms them. IEEE operations are correctly rounded, so every
// lane gets the scalar test's t, u, v and verdict bit for bit; a NaN fails a
// comparison in a lane as it does in the scalar code. Per target like
// lane_test-inl.h (Highway's per-target include guard).
#if defined(KDTREE_CC_KDTREE_LANE_FAST_TEST_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef KDTREE_CC_KDTREE_LANE_FAST_TEST_INL_H_
#undef KDTREE_CC_KDTREE_LANE_FAST_TEST_INL_H_
#else
#define KDTREE_CC_KDTREE_LANE_FAST_TEST_INL_H_
#endif

#include <cstdint>

#include "cc/geometry/ray.h"
#include "cc/kdtree/lane_test-inl.h"
#include "cc/kdtree/mask_bits-inl.h"
#include "hwy/highway.h"

HWY_BEFORE_NAMESPACE();
namespace kdtree {
namespace packet_internal {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// A ray's origin and direction in every lane.
template <class D>
struct RayLanes {
  hn::Vec<D> o[3], dir[3];
  RayLanes(D d, const Ray& ray) {
    for (int k = 0; k < 3; ++k) {
      o[k] = hn::Set(d, ray.origin[k]);
      dir[k] = hn::Set(d, ray.dir[k]);
    }
  }
};

// IntersectTriangle of the ray r against each lane's triangle t (its
// vertices by axis: x[v], y[v], z[v] of vertex a, b, c), for the lanes of
// `lanes`, with tmin < t <= tmax: out->hit gets the lanes with a hit, their
// t, u, v at the lane's index; out->scalar is empty.
template <class D>
HWY_INLINE void FastLanes(D d, const RayLanes<D>& r, const LaneTriangle<D>& t, float tmin,
                          float tmax, uint32_t lanes, LaneHits* out) {
  using V = hn::Vec<D>;
  const auto dot = [](const V a[3], const V b[3]) {
    return hn::Add(hn::Add(hn::Mul(a[0], b[0]), hn::Mul(a[1], b[1])), hn::Mul(a[2], b[2]));
  };
  const auto cross = [](const V a[3], const V b[3], V out[3]) {
    out[0] = hn::Sub(hn::Mul(a[1], b[2]), hn::Mul(a[2], b[1]));
    out[1] = hn::Sub(hn::Mul(a[2], b[0]), hn::Mul(a[0], b[2]));
    out[2] = hn::Sub(hn::Mul(a[0], b[1]), hn::Mul(a[1], b[0]));
  };
  const V a[3] = {t.x[0], t.y[0], t.z[0]};
  const V e1[3] = {hn::Sub(t.x[1], a[0]), hn::Sub(t.y[1], a[1]), hn::Sub(t.z[1], a[2])};
  const V e2[3] = {hn::Sub(t.x[2], a[0]), hn::Sub(t.y[2], a[1]), hn::Sub(t.z[2], a[2])};
  V p[3], q[3];
  cross(r.dir, e2, p);
  const V det = dot(e1, p);
  // det == 0 or NaN: parallel, degenerate or NaN.
  auto ok = hn::And(hn::Ne(det, hn::Zero(d)), hn::Eq(det, det));
  const V inv_det = hn::Div(hn::Set(d, 1.0f), det);
  const V s[3] = {hn::Sub(r.o[0], a[0]), hn::Sub(r.o[1], a[1]), hn::Sub(r.o[2], a[2])};
  const V uu = hn::Mul(dot(s, p), inv_det);
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0f);
  ok = hn::And(ok, hn::And(hn::Ge(uu, zero), hn::Le(uu, one)));
  cross(s, e1, q);
  const V vv = hn::Mul(dot(r.dir, q), inv_det);
  ok = hn::And(ok, hn::And(hn::Ge(vv, zero), hn::Le(hn::Add(uu, vv), one)));
  const V tt = hn::Mul(dot(e2, q), inv_det);
  ok = hn::And(ok, hn::And(hn::Gt(tt, hn::Set(d, tmin)), hn::Le(tt, hn::Set(d, tmax))));
  out->scalar = 0;
  out->hit = Bits(d, ok) & lanes;
  if (out->hit == 0) return;
  hn::Store(tt, d, out->t);
  hn::Store(uu, d, out->u);
  hn::Store(vv, d, out->v);
}

}  // namespace HWY_NAMESPACE
}  // namespace packet_internal
}  // namespace kdtree
HWY_AFTER_NAMESPACE();

#endif  // KDTREE_CC_KDTREE_LANE_FAST_TEST_INL_H_
