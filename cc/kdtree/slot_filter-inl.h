// The slot filter of the packet kernel through the BVH over the kd-tree's
// leaves (leaf_bvh_packet_kernel.cc): one interval test of a node's eight
// boxes for a whole group of lanes. Included once per Highway target
// (Highway's per-target include guard).
#if defined(KDTREE_CC_KDTREE_SLOT_FILTER_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef KDTREE_CC_KDTREE_SLOT_FILTER_INL_H_
#undef KDTREE_CC_KDTREE_SLOT_FILTER_INL_H_
#else
#define KDTREE_CC_KDTREE_SLOT_FILTER_INL_H_
#endif

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "cc/kdtree/leaf_bvh.h"
#include "cc/kdtree/mask_bits-inl.h"
#include "cc/kdtree/packet_rays.h"
#include "hwy/highway.h"

HWY_BEFORE_NAMESPACE();
namespace kdtree {
namespace packet_internal {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Bounds on every lane's slab distances at a node, from intervals over the
// group's lanes (Wald et al.'s packet culling; Reshetov, Soupikov & Hurley's
// frustum): each lane's origin and reciprocal lie in [lo, hi] per axis, and
// round-to-nearest subtraction and multiplication are monotone in each
// operand, so products of the interval's ends bound every lane's product as
// the lane computes it, and so do max and min. The lanes' widening, t -/+
// fl(|t| 4 u), is monotone too (leaf_bvh_test checks every finite float),
// and the bounds are widened by 8 u. So a slot whose lower bound on entry
// exceeds its upper bound on exit is entered by no lane: the per-lane test
// runs only for the other slots, and every lane's mask comes out as before.
// Only for groups whose reciprocals are all finite (a zero direction
// component makes 0 * inf possible). Camera rays share an origin, so their
// bounds are tight (lost-empire: 1.6 candidates a node, 1.6 entered); a
// shadow packet's origins are scattered (hairball-small: 3.2 candidates,
// 1.3 entered).
// In-process A/B (the filter on AVX3_DL against none on AVX3, 7 paired
// rounds, bunny, city2, lost-empire, hairball-small, courtyard-1m, teapots;
// 2026-12-06): T_R 0.958-0.998 (camera pass 0.918-0.985, shadow
// 0.920-1.006); the control, the filter on both, 0.944-1.007 with wider
// spreads: a gain of a few percent at the edge of the noise. Tried and not
// kept (same A/B): the bounds recomputed over a node's lanes when they fall
// to half of those the bounds are over (or leave them, after a pop): T_R
// 1.003-1.036, camera pass 1.016-1.054; only hairball-small's shadow pass
// gained (0.963). Nor, for shadow groups, bounds from the rays' shared end
// (d = light - o, tmax 1), the "frustum whose apex is the light"
// (2026-12-07): exactly, (plane - o) / d = 1 - (e - plane) / d with
// e = o + d, so intervals over the lanes' ends (which lie together at the
// light) and reciprocals, each rounding covered by a relative widening and
// the lane's own three roundings by 16 u, bound every lane's slab
// distance too; the tighter of the two bounds was taken. Shadow groups'
// candidates per node fell only from 5.11 to 4.68 on hairball-1m (1.38
// entered), 1.83 to 1.77 on city2 and 1.45 to 1.42 on bunny: where few
// lanes are left, the group's reciprocals (its rays' spread of
// directions) make the bounds loose, not its origins. The extra bounds
// made the shadow pass 1.13-1.21 times as long (in-process A/B, 7 paired
// rounds, hairball-1m, hairball-small, city2, bunny, morse-kitchen,
// courtyard-1m, lost-empire).
struct SlotFilter {
  bool on = false;
  float org_lo[3], org_hi[3], inv_lo[3], inv_hi[3];
  float tmin_lo = 0.0f;
  float tfar_hi = 0.0f;  // the lanes' highest best.t (+ slack, closest hit)
};

// The lowest and highest value of x (kLanes floats) over the lanes `lanes`;
// *finite becomes false if one of them is infinite or NaN.
template <class D>
HWY_INLINE void LaneRange(D d, const float* x, uint32_t lanes, float* lo, float* hi,
                          bool* finite) {
  using V = hn::Vec<D>;
  constexpr int n = static_cast<int>(hn::MaxLanes(D()));
  const V inf = hn::Set(d, INFINITY), minus_inf = hn::Set(d, -INFINITY);
  V l = inf, h = minus_inf;
  uint32_t bounded = 0;
  for (int base = 0; base < kLanes; base += n) {
    const V v = hn::Load(d, x + base);
    const auto m = FromBits(d, lanes >> base);
    l = hn::Min(l, hn::IfThenElse(m, v, inf));
    h = hn::Max(h, hn::IfThenElse(m, v, minus_inf));
    bounded |= Bits(d, hn::Lt(hn::Abs(v), inf)) << base;
  }
  *lo = hn::GetLane(hn::MinOfLanes(d, l));
  *hi = hn::GetLane(hn::MaxOfLanes(d, h));
  *finite &= (bounded & lanes) == lanes;
}

// The group's bounds; tfar_hi is set by the caller. In vectors: against a
// scalar loop over the lanes, T_R 0.968-1.001 (camera pass 0.968-0.998;
// in-process A/B, 7 paired rounds, the six scenes above, 2026-12-06; the
// same code on both sides: T_R 0.983-1.017, camera 0.986-1.004). It costs
// 12-14 ns a group (three more calls a group, a compiler barrier before
// each: bunny, city2, lost-empire, morse-indoor; 2026-12-07), about 0.12 ms
// of morse-indoor's 1.5 ms of shadow tracing. Tried and not kept: the 13
// bounds reduced together (rows of minima, the highest as minima of the
// negated values, halved by ConcatEven / ConcatOdd and Min until lane j
// holds row j's): the same bounds (packet counts identical), T_R
// 0.988-1.006, camera pass 0.979-1.009, shadow 0.996-1.011 on seven
// scenes (morse-indoor, city2, morse-kitchen, city, bunny, lost-empire,
// hairball-1m), inside the control's 0.972-1.013.
HWY_INLINE SlotFilter MakeSlotFilter(const PacketRays& p, uint32_t lanes) {
  SlotFilter f;
  const hn::ScalableTag<float> d;
  bool finite = true, ignored = true;
  for (int k = 0; k < 3; ++k) {
    LaneRange(d, p.org[k], lanes, &f.org_lo[k], &f.org_hi[k], &ignored);
    LaneRange(d, p.inv[k], lanes, &f.inv_lo[k], &f.inv_hi[k], &finite);
  }
  float tmin_hi;
  LaneRange(d, p.tmin, lanes, &f.tmin_lo, &tmin_hi, &ignored);
  f.on = finite;
  return f;
}

// The slots (bit s) some lane of the group may enter: a superset of those
// the per-lane test finds (SlotFilter). Empty slots (lo = +inf, hi = -inf)
// give an entry of +inf and an exit of -inf, and are never candidates.
HWY_INLINE uint32_t CandidateSlots(const SlotFilter& f, const LeafBvhNode& node,
                                   const int near_row[3], const int far_row[3],
                                   const bool negative[3]) {
  const hn::CappedTag<float, kBvhWidth> d;
  constexpr int n = static_cast<int>(hn::MaxLanes(d));
  using V = hn::Vec<decltype(d)>;
  const V pad = hn::Set(d, 8.0f * 0x1p-24f);
  uint32_t bits = 0;
  for (int base = 0; base < kBvhWidth; base += n) {
    V tn = hn::Set(d, f.tmin_lo);
    V tf = hn::Set(d, f.tfar_hi);
    for (int k = 0; k < 3; ++k) {
      const V o_lo = hn::Set(d, f.org_lo[k]), o_hi = hn::Set(d, f.org_hi[k]);
      const V i_lo = hn::Set(d, f.inv_lo[k]), i_hi = hn::Set(d, f.inv_hi[k]);
      const V nb = hn::LoadU(d, node.box[near_row[k]] + base);
      const V fb = hn::LoadU(d, node.box[far_row[k]] + base);
      // Positive reciprocals: the products grow with the distance to the
      // plane, so the entry's lowest uses its lowest; negative: its highest.
      const V x = negative[k] ? hn::Sub(nb, o_lo) : hn::Sub(nb, o_hi);
      const V y = negative[k] ? hn::Sub(fb, o_hi) : hn::Sub(fb, o_lo);
      tn = hn::Max(tn, hn::Min(hn::Mul(x, i_lo), hn::Mul(x, i_hi)));
      tf = hn::Min(tf, hn::Max(hn::Mul(y, i_lo), hn::Mul(y, i_hi)));
    }
    tn = hn::Sub(tn, hn::Mul(hn::Abs(tn), pad));
    tf = hn::Add(tf, hn::Mul(hn::Abs(tf), pad));
    bits |= Bits(d, hn::Le(tn, tf)) << base;
  }
  return bits;
}

}  // namespace HWY_NAMESPACE
}  // namespace packet_internal
}  // namespace kdtree
HWY_AFTER_NAMESPACE();

#endif  // KDTREE_CC_KDTREE_SLOT_FILTER_INL_H_
