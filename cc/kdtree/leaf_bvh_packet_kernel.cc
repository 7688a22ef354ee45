// Packets of 16 rays through the BVH over the kd-tree's leaves (leaf_bvh.h),
// one ray per vector lane, for every x86 target Highway knows, chosen at run
// time as the kd-tree's packet kernel is (ray_packet_kernel.cc).
//
// A group's lanes (same direction signs and watertight axes: ray_packet.cc)
// descend together: at a node, each of the eight boxes is tested against all
// lanes (Ize's conservative slab test, as the single rays'), and every child
// that some lane enters is visited with the lanes that enter it (the slots
// no lane can enter skipped first by one test for the group: SlotFilter),
// nearest first for the group's lowest lane (farthest first for any hit).
// A leaf's triangles are tested against its lanes with the kd-tree's packet
// leaf test (leaf_test-inl.h TestLeafVector). A child is dropped for a lane whose best
// hit so far ends before the child's box starts (with the slack).
//
// Any-hit groups with few lanes left at a node test each lane against the
// node's eight boxes at once instead (few_lanes-inl.h).
//
// Exactness: a lane tests every leaf whose box its ray enters before its best
// hit (the boxes and the test are the single ray's), the leaf test is exact
// per lane, and Closer's tie rule does not depend on the order in which the
// leaves come: each lane gets IntersectLeafBvh's answer, bit for bit
// (leaf_bvh_test.cc), and so the kd-tree's.
//
// Tried and not kept: leaf_bvh.h's list, "the packet kernel".
//
// Where the time goes (rdtsc around the phases, one thread, sah-packet,
// 2026-12-07; TSC ticks): 57-72 % of a render's camera packets reach no
// node (their rays miss the scene's box: 0.28-0.43 groups a packet on
// morse-indoor, city2, lost-empire, bunny, hairball-1m), yet each paid its
// set-up, about 130 ticks, 100 of them LoadLanes' eight 16-wide gathers (a
// microbenchmark on rays in L1: the gathers 100, a transposing load of the
// same rays 13, SetUpLanes 29; such a packet no longer sets up its
// watertight frames: packet_rays.h SetUpLanes). Since 2026-12-07 the rays
// are loaded by the transposing load (geometry/ray_rows-inl.h), and so are
// Embree's (embree_tracer.cc FillRay16). In a live camera group the leaves take
// 59-70 % of the kernel's time: a leaf reached costs 480-750 ticks, for
// 16-32 triangles (2.8-6.2 leaf packets at 14 lanes a triangle step, or
// 4-8 packets at about 4 rays in TestLeafFew), a node about 100-110.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "cc/kdtree/leaf_bvh_packet_kernel.cc"
#ifndef HWY_COMPILE_ALL_ATTAINABLE
#define HWY_COMPILE_ALL_ATTAINABLE
#endif
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"
#include "cc/kdtree/few_lanes-inl.h"
#include "cc/kdtree/lane_test-inl.h"
#include "cc/kdtree/leaf_test-inl.h"
#include "cc/kdtree/mask_bits-inl.h"
#include "cc/kdtree/slot_filter-inl.h"

#include <algorithm>
#include <cstdint>

#include "cc/kdtree/leaf_bvh.h"
#include "cc/kdtree/leaf_layout.h"
#include "cc/kdtree/packet_rays.h"
#include "cc/kdtree/ray_packet.h"
#include "cc/kdtree/traversal.h"

HWY_BEFORE_NAMESPACE();
namespace kdtree {
namespace packet_internal {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

static_assert(HWY_ARCH_X86, "the slab test relies on x86's max and min with a NaN operand");

struct BvhStack {
  HWY_ALIGN float t_near[kBvhWidth * kMaxTraversalStack][kLanes];
  uint32_t child[kBvhWidth * kMaxTraversalStack];
  uint32_t lanes[kBvhWidth * kMaxTraversalStack];
};

// The first three cache lines of a child some lane enters (a node, or a
// leaf's first packet), requested when the child is found rather than when
// it is reached: a child pushed on the stack waits there while its
// siblings are traced. In-process A/B (the prefetch on AVX3_DL against
// none on AVX3, 7 paired rounds, 2026-12-06): T_R 0.951 on courtyard-1m and
// 0.955 on hairball-1m (camera pass 0.944, 0.947), 0.976-0.996 on bunny,
// city2, lost-empire and hairball-small (camera 0.981-0.992); the control,
// the same code on both, T_R 0.983-1.017 (camera 0.986-1.004). A fourth
// line (a node's child indices) as well: T_R 0.979-1.008, no gain.
//
// For a closest hit, a leaf's every line instead (its packets, up to eight;
// LeafBvhNode::packets): a camera packet's leaves hold 16-32 triangles, 10
// to 20 lines, most of which it tests. In-process A/B (every line on
// AVX3_DL, three on AVX3, 7 paired rounds, three processes; 2026-12-07):
// camera pass 0.942, 0.965 and 0.943 on courtyard-1m, 0.953, 0.967 and
// 0.976 on hairball-1m, 0.977 on rungholt-1m, T_R 0.967-0.990 there; on
// city2, morse-indoor, lost-empire, hairball-small, bunny and plant-1m
// 0.96-1.02, the control's noise. For any-hit queries it was not kept: the
// shadow pass took 0.98-1.03 times as long (a shadow ray often stops
// before the leaf's end).
template <bool kAnyHit>
HWY_INLINE void PrefetchChild(const KdTree& leaves, const LeafBvhNode* nodes, uint32_t child,
                              int packets) {
  const bool leaf = (child & LeafBvhNode::kLeafBit) != 0;
  const char* q =
      leaf ? reinterpret_cast<const char*>(leaves.leaf_soa.data() +
                                           static_cast<size_t>(child & ~LeafBvhNode::kLeafBit) *
                                               kPacketFloats)
           : reinterpret_cast<const char*>(nodes + child);
  if (!kAnyHit && leaf) {
    const uintptr_t at = reinterpret_cast<uintptr_t>(q);
    const uintptr_t end = at + std::min(packets, 8) * kPacketFloats * sizeof(float);
    for (uintptr_t a = at & ~uintptr_t{63}; a < end; a += 64) {
      __builtin_prefetch(reinterpret_cast<const void*>(a));
    }
    return;
  }
  __builtin_prefetch(q);
  __builtin_prefetch(q + 64);
  __builtin_prefetch(q + 128);
}

// The lanes of all kV vectors whose rays enter slot s of `node` before
// their best hit (+ slack, closest hit): the single ray's conservative slab
// test (leaf_bvh_traversal.cc BoxRay), lane by lane; t_near (kLanes
// floats) gets each lane's widened entry distance.
template <bool kAnyHit, int kV, class D>
HWY_INLINE uint32_t EnterLanes(D d, const LeafBvhNode& node, int s, const int near_row[3],
                               const int far_row[3], const hn::Vec<D> (&org)[kV][3],
                               const hn::Vec<D> (&inv)[kV][3], const hn::Vec<D> (&tmin)[kV],
                               const hn::Vec<D> (&slack)[kV], const BestLanes<D> (&bl)[kV],
                               float* t_near) {
  using V = hn::Vec<D>;
  constexpr int n = static_cast<int>(hn::MaxLanes(D()));
  const V pad = hn::Set(d, 4.0f * 0x1p-24f);
  uint32_t m = 0;
  for (int v = 0; v < kV; ++v) {
    // As the single ray's BoxRay: a NaN slab distance is the first operand
    // of Max and Min, which then return the second.
    V tn = tmin[v];
    V tf = kAnyHit ? bl[v].t : hn::Add(bl[v].t, slack[v]);
    for (int k = 0; k < 3; ++k) {
      const V a = hn::Mul(hn::Sub(hn::Set(d, node.box[near_row[k]][s]), org[v][k]), inv[v][k]);
      const V b = hn::Mul(hn::Sub(hn::Set(d, node.box[far_row[k]][s]), org[v][k]), inv[v][k]);
      tn = hn::Max(a, tn);
      tf = hn::Min(b, tf);
    }
    tn = hn::Sub(tn, hn::Mul(hn::Abs(tn), pad));
    tf = hn::Add(tf, hn::Mul(hn::Abs(tf), pad));
    m |= Bits(d, hn::Le(tn, tf)) << (v * n);
    hn::Store(tn, d, t_near + v * n);
  }
  return m;
}

// The group's lanes in kV vectors; the descent, the leaf and the pop share
// the lanes' masks and best hits (one function, as TraceLanes). Returns the
// lanes with a hit; for the closest hit, best[i] gets the hit of each such
// lane i (any hit: best is not touched; the lanes are the answer).
template <bool kAnyHit, bool kCount, int kV, class D>
HWY_INLINE uint32_t TraceBvhLanes(D d, const LeafBvh& bvh, const PacketRays& p, const Group& g,
                                  uint32_t lanes, const SlotFilter& filter0, Hit* best,
                                  PacketCounters* counters) {
  PacketCounters* const c = kCount ? counters : nullptr;  // null: no counting code
  using V = hn::Vec<D>;
  constexpr int n = static_cast<int>(hn::MaxLanes(D()));
  static_assert(kV * n == kLanes, "the group's lanes in kV vectors");
  V org[kV][3], inv[kV][3], tmin[kV], slack[kV];
  Frames<D> frames[kV];
  BestLanes<D> bl[kV];
  for (int v = 0; v < kV; ++v) {
    for (int k = 0; k < 3; ++k) {
      org[v][k] = hn::Load(d, p.org[k] + v * n);
      inv[v][k] = hn::Load(d, p.inv[k] + v * n);
    }
    tmin[v] = hn::Load(d, p.tmin + v * n);
    slack[v] = hn::Load(d, p.slack + v * n);
    frames[v] = Frames<D>(d, p, v * n);
  }
  StartBest(d, p, bl);
  int near_row[3], far_row[3];
  for (int k = 0; k < 3; ++k) {
    near_row[k] = g.negative[k] ? 3 + k : k;
    far_row[k] = g.negative[k] ? k : 3 + k;
  }
  SlotFilter filter = filter0;
  // The lanes' highest exit bound: best.t (+ slack), lowered as hits come.
  const auto far_bound = [&] {
    V far = kAnyHit ? bl[0].t : hn::Add(bl[0].t, slack[0]);
    for (int v = 1; v < kV; ++v) far = hn::Max(far, kAnyHit ? bl[v].t : hn::Add(bl[v].t, slack[v]));
    return hn::GetLane(hn::MaxOfLanes(d, far));
  };
  filter.tfar_hi = far_bound();
  const LeafBvhNode* nodes = bvh.nodes.data();
  BvhStack stack;
  int top = 0;
  uint32_t found = 0, child = 0;
  for (;;) {
    while (!(child & LeafBvhNode::kLeafBit)) {
      const LeafBvhNode& node = nodes[child];
      if (kCount) CountStep(lanes, &c->inner_steps, &c->lanes.inner_visits);
      HWY_ALIGN float t_near[kBvhWidth][kLanes];
      uint32_t hit[kBvhWidth];
      int slots[kBvhWidth], count = 0;
      if (kAnyHit && __builtin_popcount(lanes) <= kFewLanes) {
        count = FewLaneChildren(node, p, lanes, near_row, far_row, t_near, hit, slots);
        for (int i = 0; i < count; ++i) {
          PrefetchChild<true>(bvh.leaves, nodes, node.child[slots[i]], node.packets[slots[i]]);
        }
      } else {
        uint32_t candidates = filter.on
                                  ? CandidateSlots(filter, node, near_row, far_row, g.negative)
                                  : (1u << kBvhWidth) - 1;
        for (; candidates != 0; candidates &= candidates - 1) {
          const int s = __builtin_ctz(candidates);
          if (node.child[s] == LeafBvhNode::kNone) continue;
          uint32_t m = EnterLanes<kAnyHit, kV>(d, node, s, near_row, far_row, org, inv, tmin,
                                               slack, bl, t_near[s]);
          m &= lanes;
          if (m == 0) continue;
          PrefetchChild<kAnyHit>(bvh.leaves, nodes, node.child[s], node.packets[s]);
          hit[s] = m;
          slots[count++] = s;
        }
      }
      if (count == 0) goto next;
      if (count > 1) {
        // The lowest lane's entry distances order the children: the one to
        // visit first last onto the stack.
        const int lead = __builtin_ctz(lanes);
        for (int i = 1; i < count; ++i) {
          const int s = slots[i];
          int j = i;
          while (j > 0 && (kAnyHit ? t_near[slots[j - 1]][lead] < t_near[s][lead]
                                   : t_near[slots[j - 1]][lead] > t_near[s][lead])) {
            slots[j] = slots[j - 1];
            --j;
          }
          slots[j] = s;
        }
        for (int i = count - 1; i > 0; --i) {
          const int s = slots[i];
          stack.child[top] = node.child[s];
          stack.lanes[top] = hit[s];
          if (kCount) ++c->pushes;
          for (int v = 0; v < kV; ++v) {
            hn::Store(hn::Load(d, t_near[s] + v * n), d, stack.t_near[top] + v * n);
          }
          ++top;
        }
      }
      lanes = hit[slots[0]];
      child = node.child[slots[0]];
    }
    {
      const uint32_t found_before = found;
      if (kCount) CountStep(lanes, &c->leaf_steps, &c->lanes.leaf_visits);
      for (int v = 0; v < kV; ++v) {
        TestLeafVector<kAnyHit>(d, bvh.leaves, p, frames[v], g, v * n, child & ~LeafBvhNode::kLeafBit,
                                &lanes, &found, &bl[v], c);
      }
      if (!kAnyHit && found != found_before) filter.tfar_hi = far_bound();
    }
  next:
    // Next child: each lane drops it when its box starts beyond that lane's
    // best hit plus slack (any hit: lanes with a hit are done).
    for (;;) {
      if (top == 0) {
        if (!kAnyHit) WriteBest(d, bl, found, best);
        return found;
      }
      --top;
      uint32_t m = stack.lanes[top] & ~(kAnyHit ? found : 0u);
      if (!kAnyHit && (m & found) != 0) {
        uint32_t beyond = 0;
        for (int v = 0; v < kV; ++v) {
          const V limit = hn::Add(bl[v].t, slack[v]);
          beyond |= Bits(d, hn::Gt(hn::Load(d, stack.t_near[top] + v * n), limit)) << (v * n);
        }
        m &= ~(beyond & found);
      }
      if (m == 0) continue;
      lanes = m;
      child = stack.child[top];
      break;
    }
  }
}

template <bool kCount>
HWY_INLINE uint32_t TraceBvhGroupFor(const LeafBvh& bvh, const PacketRays& p, const Group& g,
                                     bool any_hit, Hit* best, PacketCounters* c) {
  const hn::ScalableTag<float> d;
  constexpr int kV = static_cast<int>(kLanes / hn::MaxLanes(d));
  // An any-hit group of at most kFewLanes lanes never reads the filter (its
  // nodes take FewLaneChildren, and its lanes only fall), so it is not made.
  // In-process A/B (7 paired rounds, seven scenes; 2026-12-07): shadow pass
  // 0.967 on bunny and 0.974 on city2 (every round below 1), 0.984-1.004
  // elsewhere; the control (the same code on both targets) 0.995-1.008. Its
  // camera pass, unchanged code, moved 0.974-0.993 in the same run, so the
  // gain is at most a few per cent where shadow groups are small. Nor made
  // for any any-hit group (the flat scenes' shadow packets take about two
  // nodes, where the filter costs 12-14 ns a group): shadow pass 1.009-1.047
  // times as long on morse-indoor, city2, city, morse-kitchen, bunny,
  // lost-empire and hairball-1m (same A/B, 2026-12-07, a noisy state of the
  // machine): not kept.
  const SlotFilter filter = any_hit && __builtin_popcount(g.lanes) <= kFewLanes
                                ? SlotFilter()
                                : MakeSlotFilter(p, g.lanes);
  if (any_hit) {
    return TraceBvhLanes<true, kCount, kV>(d, bvh, p, g, g.lanes, filter, best, c);
  }
  return TraceBvhLanes<false, kCount, kV>(d, bvh, p, g, g.lanes, filter, best, c);
}

uint32_t TraceBvhGroupImpl(const LeafBvh& bvh, const PacketRays& p, const Group& g, bool any_hit,
                           Hit* best, PacketCounters* counters) {
  if (g.lanes == 0) return 0;
  if (counters != nullptr) return TraceBvhGroupFor<true>(bvh, p, g, any_hit, best, counters);
  return TraceBvhGroupFor<false>(bvh, p, g, any_hit, best, nullptr);
}

}  // namespace HWY_NAMESPACE
}  // namespace packet_internal
}  // namespace kdtree
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace kdtree {
namespace packet_internal {
HWY_EXPORT(TraceBvhGroupImpl);
}  // namespace packet_internal

namespace {

// Each live lane's query through `bvh`, group by group; returns the lanes
// with a hit. Closest hit: `hits` (n of them, Hit() before) get the hits of
// those lanes; any hit: hits is null. origins may be null (none). The
// callers' hits are written in place and an any-hit query's answer is the
// returned lanes, without a packet of Hits to fill, copy and read back (nor
// an array of origins to fill): in-process A/B (the change on AVX3_DL
// against the old wrappers on AVX3, 7 paired rounds; 2026-12-07), camera
// pass 0.922-0.961 of the time on morse-indoor, city2, bunny, lost-empire
// and morse-kitchen, 0.987 on hairball-1m, shadow pass 0.952-0.999, renders
// 0.949-0.987; the control (the same code on both) camera 0.987-1.003.
uint32_t TraceBvhPacket(const LeafBvh& bvh, const Ray* rays, int n, const uint32_t* origins,
                        bool any_hit, Hit* hits, PacketCounters* counters) {
  return packet_internal::TracePacketGroups(
      bvh.leaves, rays, n, origins, counters,
      [&](const packet_internal::PacketRays& p, const packet_internal::Group& g) {
        return HWY_DYNAMIC_DISPATCH(packet_internal::TraceBvhGroupImpl)(bvh, p, g, any_hit, hits,
                                                                        counters);
      });
}

}  // namespace

void IntersectPacketLeafBvh(const LeafBvh& bvh, const Ray* rays, int n, Hit* hits,
                            PacketCounters* counters) {
  if (bvh.nodes.empty()) {
    for (int i = 0; i < n; ++i) hits[i] = IntersectLeafBvh(bvh, rays[i]);
    return;
  }
  for (int i = 0; i < n; ++i) hits[i] = Hit();
  TraceBvhPacket(bvh, rays, n, nullptr, false, hits, counters);
}

void OccludedPacketLeafBvh(const LeafBvh& bvh, const Ray* rays, int n,
                           const uint32_t* origin_tris, bool* occluded,
                           PacketCounters* counters) {
  if (bvh.nodes.empty()) {
    for (int i = 0; i < n; ++i) occluded[i] = false;
    return;
  }
  const uint32_t found = TraceBvhPacket(bvh, rays, n, origin_tris, true, nullptr, counters);
  for (int i = 0; i < n; ++i) occluded[i] = (found >> i) & 1;
}

}  // namespace kdtree
#endif  // HWY_ONCE
