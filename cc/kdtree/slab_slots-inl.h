// One ray against a node's eight boxes (leaf_bvh.h) in vectors of D, a
// node's slots in whole vectors: the conservative slab test of the BVH's
// single rays (leaf_bvh_traversal.cc, on the build's static target) and of
// a packet's lanes taken one at a time (few_lanes-inl.h, per target). Per
// target (Highway's per-target include guard).
//
// A direction component of +-0 (or whose reciprocal overflows) gives an
// infinite reciprocal, and a slab distance (b - o) * inf is NaN when the
// origin lies on the slab's plane; the distances are combined so that a NaN
// is passed over (x86's max and min return their second operand when one is
// NaN, and a NaN is only ever the first): the slab then bounds nothing,
// right for a ray that runs in the plane of a closed box's face.
//
// Tried and not kept (single rays, kd_bvh; 2026-12-07): each slab distance
// as one fused multiply-subtract, box * inv - o * inv, with o * inv set up
// once per ray and moved by 2^-21 of itself to cover its rounding (a
// widening absolute in t, where the one below is relative to t), and the
// three maxima and minima as a tree; rays with a reciprocal infinite or
// zero, or o * inv infinite, took the test below. Shorter by a subtraction
// and a max on each node's dependent chain, yet (pair_variants, the fused
// test behind a scratch switch in the same binary, 21 paired rounds, seven
// scenes) camera pass 0.976-1.028, the noise, and the shadow pass 1.31
// times as long on courtyard-1m, 1.12 on city2 and 1.67 on lost-empire,
// 0.99-1.04 on the others. Presumably the widening, which does not shrink
// to zero at the ray's origin as the relative one does, lets a shadow ray
// enter the flat boxes of the plane it leaves (leaf_bvh.h's padded boxes,
// tried first, lost on lost-empire in the same way).
#if defined(KDTREE_CC_KDTREE_SLAB_SLOTS_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef KDTREE_CC_KDTREE_SLAB_SLOTS_INL_H_
#undef KDTREE_CC_KDTREE_SLAB_SLOTS_INL_H_
#else
#define KDTREE_CC_KDTREE_SLAB_SLOTS_INL_H_
#endif

#include <cstdint>

#include "cc/kdtree/leaf_bvh.h"
#include "cc/kdtree/mask_bits-inl.h"
#include "hwy/highway.h"

HWY_BEFORE_NAMESPACE();
namespace kdtree {
namespace packet_internal {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

static_assert(HWY_ARCH_X86, "the slab test relies on x86's max and min with a NaN operand");

// The slots of `node` whose boxes the ray (origin o, reciprocal direction
// inv, per axis in every lane; near_row and far_row: its LeafBvhNode::box
// rows by direction sign) enters within [tmin, limit] (bit s: slot s),
// conservatively (the interval widened by 4 u a side: leaf_bvh.h), and
// where it enters each (t_near, kBvhWidth floats).
//
// kScaled, for tmin >= 0 only: the widening as one multiplication a side,
// tn * (1 - 4 u) and tf * (1 + 4 u), instead of tn - |tn| 4 u and tf + |tf|
// 4 u (u = 2^-24). The same numbers wherever |t| 4 u is a normal float
// (|t| >= 2^-104): it is then exact (4 u = 2^-22), so both forms round
// t (1 -+ 4 u) once; below that they may differ by an ulp, this form being
// t (1 -+ 4 u) correctly rounded, so the widening by 4 u holds at least as
// well. tn >= tmin >= 0 (a NaN slab distance yields to the running tn,
// above); where tf < 0 the two forms differ, but both are then below tn's
// widened value, so the mask is the same. (The one exception: a slab
// distance of +inf, from a direction component of zero or an overflow,
// gives NaN in the other form, a miss, and +inf here, which enters a box
// only through another +inf: a box more, never one less.) It takes two
// operations off each node's dependent chain: single rays (kd_bvh,
// in-process A/B, 21 paired rounds; city2, lost-empire, courtyard-1m,
// bunny, teapots, hairball-1m, rungholt-1m, fforest; 2026-12-08): T_R
// 0.970-0.978 of the time, the camera pass alone 0.961-0.976, the shadow
// pass 0.935-0.977. Tried with it and not kept: the three maxima and the
// three minima as trees (T_R 1.004-1.010, camera pass 1.010-1.018); the
// same widening in the packet kernel's EnterLanes, for groups whose lanes
// all have tmin >= 0 (kd_bvh_packet, same A/B: T_R 0.998-1.014, camera
// pass 1.001-1.032): there the lanes' tests do not form one chain.
template <class D, bool kScaled = false>
HWY_INLINE uint32_t RaySlots(D d, const LeafBvhNode& node, const hn::Vec<D> (&o)[3],
                             const hn::Vec<D> (&inv)[3], const int near_row[3],
                             const int far_row[3], float tmin, float limit, float* t_near) {
  using V = hn::Vec<D>;
  constexpr int n = static_cast<int>(hn::MaxLanes(D()));
  static_assert(kBvhWidth % n == 0, "a node's slots in whole vectors");
  const V pad = hn::Set(d, 4.0f * 0x1p-24f);
  uint32_t mask = 0;
  for (int c = 0; c < kBvhWidth; c += n) {
    V tn = hn::Set(d, tmin), tf = hn::Set(d, limit);
    for (int k = 0; k < 3; ++k) {
      const V a = hn::Mul(hn::Sub(hn::Load(d, node.box[near_row[k]] + c), o[k]), inv[k]);
      const V b = hn::Mul(hn::Sub(hn::Load(d, node.box[far_row[k]] + c), o[k]), inv[k]);
      tn = hn::Max(a, tn);
      tf = hn::Min(b, tf);
    }
    if (kScaled) {
      tn = hn::Mul(tn, hn::Set(d, 1.0f - 4.0f * 0x1p-24f));
      tf = hn::Mul(tf, hn::Set(d, 1.0f + 4.0f * 0x1p-24f));
    } else {
      tn = hn::Sub(tn, hn::Mul(hn::Abs(tn), pad));
      tf = hn::Add(tf, hn::Mul(hn::Abs(tf), pad));
    }
    mask |= Bits(d, hn::Le(tn, tf)) << c;
    hn::Store(tn, d, t_near + c);
  }
  return mask;
}

}  // namespace HWY_NAMESPACE
}  // namespace packet_internal
}  // namespace kdtree
HWY_AFTER_NAMESPACE();

#endif  // KDTREE_CC_KDTREE_SLAB_SLOTS_INL_H_
