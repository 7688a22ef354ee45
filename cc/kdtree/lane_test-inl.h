// The watertight ray-triangle test (cc/geometry/watertight.h) for one
// triangle against a vector of rays, one ray per lane, for the packet kernel
// (ray_packet_kernel.cc); per target like it (Highway's per-target include
// guard).
//
// ShearLanes and RejectRays are the test's first step and edge bound, each
// lane with its own ray and triangle (one triangle for all lanes, or a few
// rays against a leaf packet's four triangles), with the same IEEE operations
// in the same order as Shear and EdgeErrorBound, so a lane RejectRays sets
// is a lane the test rejects. FinishLanes then runs the rest of the test for
// the common case, a ray whose three edge functions have decided, agreeing
// signs: watertight.h's Finish, in double vectors with Finish's operations
// in Finish's order (each IEEE operation is correctly rounded, so every lane
// gets the scalar test's floats: t, u, v bit for bit). The rare lanes (an
// undecided sign, a projected area within rounding of zero, a triangle
// across the origin's depth with t within rounding of tmin) are returned for
// the scalar test itself. The single-ray traversal (traversal.cc) runs them
// too, with one ray in every lane and a leaf packet's four triangles.
#if defined(KDTREE_CC_KDTREE_LANE_TEST_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef KDTREE_CC_KDTREE_LANE_TEST_INL_H_
#undef KDTREE_CC_KDTREE_LANE_TEST_INL_H_
#else
#define KDTREE_CC_KDTREE_LANE_TEST_INL_H_
#endif

#include <cmath>
#include <cstdint>

#include "cc/geometry/float_bits.h"
#include "cc/geometry/watertight.h"
#include "cc/kdtree/leaf_layout.h"
#include "cc/kdtree/mask_bits-inl.h"
#include "cc/kdtree/packet_rays.h"
#include "hwy/highway.h"

HWY_BEFORE_NAMESPACE();
namespace kdtree {
namespace packet_internal {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

template <class D>
HWY_INLINE hn::Vec<D> MaxAbs3(const hn::Vec<D> v[3]) {
  return hn::Max(hn::Max(hn::Abs(v[0]), hn::Abs(v[1])), hn::Abs(v[2]));
}

// The lanes' watertight frames and tmin, loaded once per vector of lanes.
template <class D>
struct Frames {
  hn::Vec<D> ox, oy, oz, sx, sy, sz, shear_weight, tmin;
  Frames() = default;
  Frames(D d, const PacketRays& p, size_t base)
      : ox(hn::Load(d, p.ox + base)),
        oy(hn::Load(d, p.oy + base)),
        oz(hn::Load(d, p.oz + base)),
        sx(hn::Load(d, p.sx + base)),
        sy(hn::Load(d, p.sy + base)),
        sz(hn::Load(d, p.sz + base)),
        shear_weight(hn::Load(d, p.shear_weight + base)),
        tmin(hn::Load(d, p.tmin + base)) {}
  // One ray (its watertight frame, its tmin) in every lane.
  Frames(D d, const WatertightRay& w, float ray_tmin)
      : ox(hn::Set(d, w.ox)),
        oy(hn::Set(d, w.oy)),
        oz(hn::Set(d, w.oz)),
        sx(hn::Set(d, w.sx)),
        sy(hn::Set(d, w.sy)),
        sz(hn::Set(d, w.sz)),
        shear_weight(hn::Set(d, watertight_internal::ShearWeight(w))),
        tmin(hn::Set(d, ray_tmin)) {}
  // Lane j of the result is lane idx[j] of this (idx: SetTableIndices).
  template <class I>
  Frames Permuted(I idx) const {
    Frames f;
    f.ox = hn::TableLookupLanes(ox, idx);
    f.oy = hn::TableLookupLanes(oy, idx);
    f.oz = hn::TableLookupLanes(oz, idx);
    f.sx = hn::TableLookupLanes(sx, idx);
    f.sy = hn::TableLookupLanes(sy, idx);
    f.sz = hn::TableLookupLanes(sz, idx);
    f.shear_weight = hn::TableLookupLanes(shear_weight, idx);
    f.tmin = hn::TableLookupLanes(tmin, idx);
    return f;
  }
};

// A triangle's vertices per lane, the group's axes kx, ky, kz of vertex v in
// x[v], y[v], z[v].
template <class D>
struct LaneTriangle {
  hn::Vec<D> x[3], y[3], z[3];
};

// Triangle l of a leaf packet in every lane (one triangle, a ray per lane).
template <class D>
HWY_INLINE LaneTriangle<D> BroadcastTriangle(D d, const Group& g, const float* packet, int l) {
  LaneTriangle<D> t;
  for (int v = 0; v < 3; ++v) {
    const float* q = packet + 3 * v * kPacketLanes + l;
    t.x[v] = hn::Set(d, q[g.kx * kPacketLanes]);
    t.y[v] = hn::Set(d, q[g.ky * kPacketLanes]);
    t.z[v] = hn::Set(d, q[g.kz * kPacketLanes]);
  }
  return t;
}

// The leaf packet's kPacketLanes triangles in every block of kPacketLanes
// lanes: lane j holds triangle j % kPacketLanes (a few rays, four triangles
// each).
template <class D>
HWY_INLINE LaneTriangle<D> RepeatTriangles(D d, const Group& g, const float* packet) {
  static_assert(kPacketLanes == 4, "one leaf packet per 128-bit block");
  LaneTriangle<D> t;
  for (int v = 0; v < 3; ++v) {
    const float* q = packet + 3 * v * kPacketLanes;
    t.x[v] = hn::LoadDup128(d, q + g.kx * kPacketLanes);
    t.y[v] = hn::LoadDup128(d, q + g.ky * kPacketLanes);
    t.z[v] = hn::LoadDup128(d, q + g.kz * kPacketLanes);
  }
  return t;
}

// The triangle in every lane's sheared frame (watertight.h Shear: x, y, dz
// and the edge functions e) and the edge functions' error bound
// (EdgeErrorBound).
template <class D>
struct LaneShear {
  hn::Vec<D> x[3], y[3], dz[3], e[3], bound;
};

// Tried and not kept: for a camera packet (lanes sharing one origin), one
// bound per leaf triangle for all lanes, computed once per leaf packet in a
// 4-lane pass (each sheared coordinate bounded at the two ends of the lanes'
// range of shears, where the rounded expression is monotone; a larger bound
// only leaves more lanes to the exact tests). 18 fewer wide operations per
// triangle step, and the camera pass took 0.989-1.026 of the time
// (in-process A/B, 7 paired rounds, eight scenes, 2026-12-06): the leaf step
// is not bound by its arithmetic.
// Nor, for lanes that share their origin o exactly (camera packets), a filter
// before the shear (2026-12-07): per leaf packet, in one 4-lane pass, each
// triangle's normals N_U = (c - b) x (b - o), N_V = (a - c) x (c - o), N_W =
// (b - a) x (a - o) (equal to (c - o) x (b - o) and its cyclic versions, but
// rounded relative to |edge| |offset|); a lane's dot products with them have
// the exact edge functions' signs, the signs the test acts on (watertight.h),
// and a bound on their rounding (16 gamma_8 times the largest |edge| |offset|
// product times the group's largest |d|_1, plus a term for underflow; infinite
// past 2^100) lets a lane be rejected only when two of them have certainly
// opposite signs. A unit test against exact_triple.h's signs (rays at vertices,
// edges and the floats beside them; triangles of 0.3 to 1e-5 of their distance;
// scales 1e-15 to 1e30) found no lane rejected wrongly. In the kernel it
// rejected every lane in 73-83 % of TestLeaf's triangle steps (bunny, city2,
// lost-empire, hairball-1m), and the whole test then rejected every lane in
// 2-4 % of the rest (15 % on hairball-1m). Yet (in-process A/B, AVX3_DL against
// AVX3, 7 paired rounds, kd_bvh_packet; bunny, city2, lost-empire, hairball-1m,
// courtyard-1m) the camera pass took 1.01-1.04 times as long with the filter in
// TestLeaf's loop, and 0.97-1.01 (the control's noise) with the filter first
// run over eight leaf packets at a time without a branch on its result and the
// shear then run only for the steps some lane survives. The filter's pass alone
// (its result discarded) made the camera pass 1.03-1.15 times as long
// (hairball-1m 1.03, bunny 1.15), so the steps it saves cost about as much;
// running TestLeaf twice on every leaf (warm the second time) made it 1.23-1.35
// times as long. So the leaf's work is a quarter to a third of the camera pass,
// up to half of it (bunny) in the triangle steps every lane rejects, and three
// dot products a lane plus the per-packet normals cost about what the shear
// they replace does. The whole-packet cull (leaf_test-inl.h) failed for the
// same reason.
template <class D>
HWY_INLINE LaneShear<D> ShearLanes(D d, const Frames<D>& f, const LaneTriangle<D>& t) {
  using V = hn::Vec<D>;
  LaneShear<D> s;
  for (int v = 0; v < 3; ++v) {
    s.dz[v] = hn::Sub(t.z[v], f.oz);
    s.x[v] = hn::Sub(hn::Sub(t.x[v], f.ox), hn::Mul(f.sx, s.dz[v]));
    s.y[v] = hn::Sub(hn::Sub(t.y[v], f.oy), hn::Mul(f.sy, s.dz[v]));
  }
  s.e[0] = hn::Sub(hn::Mul(s.x[2], s.y[1]), hn::Mul(s.y[2], s.x[1]));
  s.e[1] = hn::Sub(hn::Mul(s.x[0], s.y[2]), hn::Mul(s.y[0], s.x[2]));
  s.e[2] = hn::Sub(hn::Mul(s.x[1], s.y[0]), hn::Mul(s.y[1], s.x[0]));
  const V lmax = hn::Max(MaxAbs3<D>(s.x), MaxAbs3<D>(s.y));
  const V depth = hn::Mul(
      hn::Add(MaxAbs3<D>(s.dz), hn::Set(d, watertight_internal::kEdgeBoundMinDepth)),
      f.shear_weight);
  s.bound = hn::Add(hn::Mul(hn::Set(d, watertight_internal::kEdgeBoundRel),
                            hn::Mul(lmax, hn::Add(lmax, depth))),
                    hn::Set(d, watertight_internal::kEdgeBoundAbs));
  return s;
}

// The lanes whose edge functions certainly disagree in sign (SignsDisagree).
template <class D>
HWY_INLINE uint32_t DisagreeLanes(D d, const LaneShear<D>& s) {
  const auto e_max = hn::Max(hn::Max(s.e[0], s.e[1]), s.e[2]);
  const auto e_min = hn::Min(hn::Min(s.e[0], s.e[1]), s.e[2]);
  return Bits(d, hn::And(hn::Gt(e_max, s.bound), hn::Lt(e_min, hn::Neg(s.bound))));
}

// The lanes whose three vertex depths z = sz dz are negative (the test's
// "behind" rejection; it applies to lanes with tmin >= 0 only).
template <class D>
HWY_INLINE uint32_t BehindLanes(D d, const Frames<D>& f, const LaneShear<D>& s) {
  const auto zero = hn::Zero(d);
  return Bits(d, hn::And(hn::And(hn::Lt(hn::Mul(f.sz, s.dz[0]), zero),
                                 hn::Lt(hn::Mul(f.sz, s.dz[1]), zero)),
                         hn::Lt(hn::Mul(f.sz, s.dz[2]), zero)));
}

// The lanes (rays) that certainly miss the triangle of s; `behind`: the lanes
// with tmin >= 0 the behind rejection is worth trying on.
template <class D>
HWY_INLINE uint32_t RejectRays(D d, const Frames<D>& f, const LaneShear<D>& s, uint32_t behind) {
  uint32_t reject = DisagreeLanes(d, s);
  if (behind != 0) reject |= BehindLanes(d, f, s) & behind;
  return reject;
}

// What FinishLanes found: the lanes with a hit (t, u, v at the lane's index,
// unless given as LaneHitVecs) and the lanes left to the scalar test.
struct LaneHits {
  uint32_t hit = 0, scalar = 0;
  HWY_ALIGN float t[kLanes];
  HWY_ALIGN float u[kLanes];
  HWY_ALIGN float v[kLanes];
};

// FinishLanes' hits as vectors: t, u, v in the lanes of LaneHits::hit, the
// other lanes unspecified.
template <class D>
struct LaneHitVecs {
  hn::Vec<D> t, u, v;
};

// IntersectTriangleWatertight after RejectRays, for the `lanes` it did not
// reject (t_max: each lane's tmax, its best hit's t so far), the triangle's
// shear s. A lane in neither out->hit nor out->scalar misses. The hits' t,
// u, v go to vecs if given (the packet kernel keeps its best hits in
// vectors), else to out->t, u, v.
// Both halves computed without the branches on an empty half and on no hit
// (a simulated predictor counted them among the kernel's least predictable)
// made the packet kernel 0.3-2 % slower (in-process A/B, six scenes,
// 2026-12-06): not kept. Nor the bounds skipped where they cannot decide (a
// half with no lane in range left at once; the bound of a triangle across
// the origin's depth only for lanes with such a triangle): though perf
// charges a fifth of the camera packets' kernel samples to FinishLanes
// (armadillo), camera pass 0.978-0.995 of the time on bunny, armadillo,
// refined-elephant, city2 and lost-empire, the control 0.983-1.004
// (pair_variants, 21 paired rounds, 2026-12-07).
template <class D>
HWY_INLINE void FinishLanes(D d, const Frames<D>& f, const LaneShear<D>& s, uint32_t lanes,
                            hn::Vec<D> t_max, LaneHits* out, LaneHitVecs<D>* vecs = nullptr) {
#if HWY_TARGET == HWY_SCALAR
  out->hit = 0;
  out->scalar = lanes;  // no half vectors: the scalar test does it all
  (void)d, (void)f, (void)s, (void)t_max, (void)vecs;
#else
  using V = hn::Vec<D>;
  const V z[3] = {hn::Mul(f.sz, s.dz[0]), hn::Mul(f.sz, s.dz[1]), hn::Mul(f.sz, s.dz[2])};
  const uint32_t decided = Bits(d, hn::And(hn::And(hn::Gt(hn::Abs(s.e[0]), s.bound),
                                                   hn::Gt(hn::Abs(s.e[1]), s.bound)),
                                           hn::Gt(hn::Abs(s.e[2]), s.bound)));
  out->scalar = lanes & ~decided;
  out->hit = 0;
  lanes &= decided;
  if (lanes == 0) return;
  // Finish's inputs, per lane, in float.
  const V max_x = MaxAbs3<D>(s.x), max_y = MaxAbs3<D>(s.y), max_z = MaxAbs3<D>(z);
  const V max_abs_kz = MaxAbs3<D>(s.dz);
  const V min_z = hn::Min(hn::Min(z[0], z[1]), z[2]);
  const hn::Half<D> dh;
  const hn::Repartition<double, D> dd;
  using VD = hn::Vec<decltype(dd)>;
  const size_t half = hn::Lanes(dh);
  const uint32_t half_bits = (1u << half) - 1;
  using VH = hn::Vec<decltype(dh)>;
  VH t_half[2] = {hn::Zero(dh), hn::Zero(dh)}, u_half[2] = {t_half[0], t_half[0]},
     v_half[2] = {t_half[0], t_half[0]};
  for (size_t h = 0; h < 2; ++h) {
    const uint32_t mine = (lanes >> (h * half)) & half_bits;
    if (mine == 0) continue;
    const auto wide = [&](V v) {
      return h == 0 ? hn::PromoteTo(dd, hn::LowerHalf(dh, v)) : hn::PromoteTo(dd, hn::UpperHalf(dh, v));
    };
    const auto narrow = [&](V v) { return h == 0 ? hn::LowerHalf(dh, v) : hn::UpperHalf(dh, v); };
    const VD e0 = wide(s.e[0]), e1 = wide(s.e[1]), e2 = wide(s.e[2]);
    const VD det = hn::Add(hn::Add(e0, e1), e2);
    const VD big_t = hn::Add(hn::Add(hn::Mul(e0, wide(z[0])), hn::Mul(e1, wide(z[1]))),
                             hn::Mul(e2, wide(z[2])));
    const VD inv_det = hn::Div(hn::Set(dd, 1.0), det);
    const auto tt = hn::DemoteTo(dh, hn::Mul(big_t, inv_det));
    const uint32_t in_range =
        Bits(dh, hn::And(hn::Le(tt, narrow(t_max)), hn::Lt(tt, hn::Set(dh, INFINITY))));
    // The rounding bounds (Finish): a projected area within rounding of
    // zero, or a triangle spanning the origin's depth, goes to the scalar
    // test; else t > tmin decides.
    const VD mx = wide(max_x), my = wide(max_y);
    const VD delta_x = hn::Mul(hn::Set(dd, double(Gamma(5))), hn::Add(mx, wide(max_abs_kz)));
    const VD delta_y = hn::Mul(hn::Set(dd, double(Gamma(5))), hn::Add(my, wide(max_abs_kz)));
    const VD delta_e = hn::Mul(
        hn::Set(dd, 2.0),
        hn::Add(hn::Add(hn::Mul(hn::Mul(hn::Set(dd, double(Gamma(2))), mx), my),
                        hn::Mul(delta_y, mx)),
                hn::Mul(delta_x, my)));
    const uint32_t near_zero =
        Bits(dd, hn::Le(hn::Abs(det), hn::Mul(hn::Set(dd, 3.0), delta_e)));
    const VD mz = wide(max_z);
    const VD delta_z = hn::Mul(hn::Set(dd, double(Gamma(3))), mz);
    const uint32_t front = Bits(dd, hn::Gt(wide(min_z), delta_z));
    const uint32_t beyond_tmin = Bits(dh, hn::Gt(tt, narrow(f.tmin)));
    // A triangle across the origin's depth: t against tmin outside the bound
    // on its rounding; inside it, the scalar test decides exactly.
    const VD max_e = wide(MaxAbs3<D>(s.e));
    const VD delta_t = hn::Mul(
        hn::Mul(hn::Set(dd, 3.0),
                hn::Add(hn::Add(hn::Mul(hn::Mul(hn::Set(dd, double(Gamma(3))), max_e), mz),
                                hn::Mul(delta_e, mz)),
                        hn::Mul(delta_z, max_e))),
        hn::Abs(inv_det));
    const VD t_wide = hn::PromoteTo(dd, tt), tmin = wide(f.tmin);
    const uint32_t below = Bits(dd, hn::Le(t_wide, hn::Sub(tmin, delta_t)));
    const uint32_t above = Bits(dd, hn::Gt(t_wide, hn::Add(tmin, delta_t)));
    const uint32_t go_on = mine & in_range & ~near_zero;
    const uint32_t scalar = (mine & in_range & near_zero) | (go_on & ~front & ~below & ~above);
    const uint32_t hit = go_on & ((front & beyond_tmin) | (~front & above));
    out->scalar |= scalar << (h * half);
    out->hit |= hit << (h * half);
    if (hit == 0) continue;
    t_half[h] = tt;
    u_half[h] = hn::DemoteTo(dh, hn::Mul(e1, inv_det));
    v_half[h] = hn::DemoteTo(dh, hn::Mul(e2, inv_det));
    if (vecs == nullptr) {
      hn::StoreU(tt, dh, out->t + h * half);
      hn::StoreU(u_half[h], dh, out->u + h * half);
      hn::StoreU(v_half[h], dh, out->v + h * half);
    }
  }
  if (vecs != nullptr) {
    vecs->t = hn::Combine(d, t_half[1], t_half[0]);
    vecs->u = hn::Combine(d, u_half[1], u_half[0]);
    vecs->v = hn::Combine(d, v_half[1], v_half[0]);
  }
#endif
}

}  // namespace HWY_NAMESPACE
}  // namespace packet_internal
}  // namespace kdtree
HWY_AFTER_NAMESPACE();

#endif  // KDTREE_CC_KDTREE_LANE_TEST_INL_H_
