// The node step of the BVH packet kernel for a group with few lanes left,
// per target like the kernel (Highway's per-target include guard).
//
// Any-hit groups of the packet kernel through the BVH over the kd-tree's leaves
// (leaf_bvh_packet_kernel.cc) with few lanes left at a node (kFewLanes, 4) test
// each lane against the eight boxes at once (LaneSlots: the single ray's form,
// EnterLanes' operations) instead of the group's slot filter and a 16-lane test
// per candidate slot. Exact: LaneSlots runs EnterLanes' float operations in
// EnterLanes' order, so each lane enters the slots it entered before, and every
// answer is the single ray's. Shadow rays diverge (hairball-1m: 3.0 lanes a
// node step), and there the group's filter is loose: 5.1 candidate slots a node
// for 1.4 entered. In-process A/B (the per-lane test on AVX3_DL against none on
// AVX3, 7 paired rounds, 2026-12-07): shadow pass 0.875-0.896 on hairball-1m
// (T_R 0.938-0.945, three runs), 0.945-0.970 on courtyard-1m, 0.96-0.98 on
// fforest, teapots, morse-indoor, stk-black-forest and rungholt-1m, 0.98-1.01
// on city2, bunny, morse-kitchen, lost-empire, hairball-small and plant-1m;
// camera pass 0.99-1.02 (untouched). Up to 8 lanes: hairball-1m 0.877, but
// 1.006-1.031 on five other scenes; up to 6, as 4. For closest-hit groups as
// well (each lane's entry distances kept for the pop): camera pass 1.007-1.067,
// and with at most 2 lanes 0.993-1.028 (six scenes), so not kept. The full
// sweep after it (README): hairball-1m's best mode 0.87 -> 0.93 of Embree's,
// its shadow packets 0.69 -> 0.80. It runs on every target with 8-lane float
// vectors (AVX2 and up); leaf_bvh_test checks it on each.
#if defined(KDTREE_CC_KDTREE_FEW_LANES_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef KDTREE_CC_KDTREE_FEW_LANES_INL_H_
#undef KDTREE_CC_KDTREE_FEW_LANES_INL_H_
#else
#define KDTREE_CC_KDTREE_FEW_LANES_INL_H_
#endif

#include <cstdint>

#include "cc/kdtree/leaf_bvh.h"
#include "cc/kdtree/mask_bits-inl.h"
#include "cc/kdtree/packet_rays.h"
#include "cc/kdtree/slab_slots-inl.h"
#include "hwy/highway.h"

HWY_BEFORE_NAMESPACE();
namespace kdtree {
namespace packet_internal {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Lane i's slab test of the node's eight boxes in one 8-wide vector, the
// single ray's (RaySlots), from its far bound `far` (EnterLanes' tf before
// the boxes): EnterLanes' float operations in EnterLanes' order, so the
// lane enters the same slots; t_near8 gets its eight widened entry
// distances.
template <class D8>
HWY_INLINE uint32_t LaneSlots(D8 d8, const LeafBvhNode& node, const PacketRays& p, int i,
                              float far, const int near_row[3], const int far_row[3],
                              float* t_near8) {
  hn::Vec<D8> o[3], inv[3];
  for (int k = 0; k < 3; ++k) {
    o[k] = hn::Set(d8, p.org[k][i]);
    inv[k] = hn::Set(d8, p.inv[k][i]);
  }
  return RaySlots(d8, node, o, inv, near_row, far_row, p.tmin[i], far, t_near8);
}

// Up to how many lanes of an any-hit group take LaneSlots at a node instead
// of the slot filter and EnterLanes (targets with 8-lane float vectors).
constexpr int kFewLanes =
    hn::MaxLanes(hn::CappedTag<float, kBvhWidth>()) == kBvhWidth ? 4 : 0;

// A node's children for an any-hit group with at most kFewLanes lanes left:
// each lane's LaneSlots (a live any-hit lane's best t is its tmax:
// EnterLanes' tf). Fills hit[s] (the lanes that enter slot s), slots (the
// entered slots, in slot order, as the per-slot loop finds them) and
// t_near[s][lead] for the lowest lane's ordering; returns how many.
HWY_INLINE int FewLaneChildren(const LeafBvhNode& node, const PacketRays& p, uint32_t lanes,
                               const int near_row[3], const int far_row[3],
                               float (*t_near)[kLanes], uint32_t* hit, int* slots) {
  const hn::CappedTag<float, kBvhWidth> d8;
  uint32_t nonempty = 0;
  for (int q = 0; q < kBvhWidth; ++q) {
    nonempty |= static_cast<uint32_t>(node.child[q] != LeafBvhNode::kNone) << q;
  }
  uint32_t lane_hits[kBvhWidth] = {0, 0, 0, 0, 0, 0, 0, 0};
  HWY_ALIGN float lead_t[kBvhWidth], other_t[kBvhWidth];
  const int lead = __builtin_ctz(lanes);
  uint32_t entered = 0;
  for (uint32_t m = lanes; m != 0; m &= m - 1) {
    const int i = __builtin_ctz(m);
    const uint32_t sm =
        LaneSlots(d8, node, p, i, p.tmax[i], near_row, far_row, i == lead ? lead_t : other_t) &
        nonempty;
    entered |= sm;
    for (uint32_t q = sm; q != 0; q &= q - 1) lane_hits[__builtin_ctz(q)] |= 1u << i;
  }
  int count = 0;
  for (; entered != 0; entered &= entered - 1) {
    const int s = __builtin_ctz(entered);
    t_near[s][lead] = lead_t[s];
    hit[s] = lane_hits[s];
    slots[count++] = s;
  }
  return count;
}

}  // namespace HWY_NAMESPACE
}  // namespace packet_internal
}  // namespace kdtree
HWY_AFTER_NAMESPACE();

#endif  // KDTREE_CC_KDTREE_FEW_LANES_INL_H_
