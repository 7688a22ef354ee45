// The packet traversal's kernel, one ray per vector lane, compiled for every
// x86 target Highway knows (SSE4: 4 lanes, AVX2: 8, AVX-512: 16, ...) and
// chosen at run time for the CPU (Highway's dynamic dispatch: foreach_target.h
// re-includes this file once per target).
//
// Wald, Slusallek, Benthin & Wagner, "Interactive rendering with coherent ray
// tracing", CGF 20(3), 2001, and Wald's thesis (Saarland University, 2004,
// section 7.2): rays with the same direction signs agree on the near child of
// every node, so they descend together, each lane with its own interval. A
// node, a leaf and a leaf's triangles are loaded once for all lanes, and a
// triangle is tested against all lanes at once (the leaf loop is over
// triangles, the vector over rays), which is what makes wide vectors pay.
// Where the lanes diverge and few of them reach a leaf, each ray is tested
// against a leaf packet's four triangles at once instead (leaf_test-inl.h
// TestLeafFew; the switch of Benthin, Wald, Woop, Ernst & Mark, "Combining
// single and packet-ray tracing for arbitrary ray distributions on the Intel
// MIC architecture", IEEE TVCG 18(9), 2012, made per leaf).
//
// Exactness (ray_packet.h): every lane applies the single-ray traversal's rules
// (traversal.h) with the same float operations to the same intervals, and
// drops a popped node when its own best hit rules it out, so it visits the
// nodes the single-ray traversal visits. Per triangle, the watertight test
// runs on all lanes at once with its own IEEE operations in its own order
// (lane_test-inl.h): the common rejection, whose set lanes are certain
// misses, then the rest of the test in double vectors for the lanes with
// decided signs; the rare lanes left (undecided signs, near-zero area, t
// within rounding of tmin) get the scalar IntersectTriangleWatertight itself.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "cc/kdtree/ray_packet_kernel.cc"
// Every target the compiler can build, also under -march=native, so that the
// tests run the 4- and 8-lane kernels on a machine with AVX-512.
#ifndef HWY_COMPILE_ALL_ATTAINABLE
#define HWY_COMPILE_ALL_ATTAINABLE
#endif
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"
// Per target, after foreach_target.h:
#include "cc/kdtree/lane_test-inl.h"
#include "cc/kdtree/leaf_test-inl.h"
#include "cc/kdtree/mask_bits-inl.h"

#include <cmath>
#include <cstdint>

#include "cc/geometry/watertight.h"
#include "cc/kdtree/leaf_layout.h"
#include "cc/kdtree/packet_rays.h"
#include "cc/kdtree/ray_setup.h"
#include "cc/kdtree/ray_packet.h"
#include "cc/kdtree/traversal.h"

HWY_BEFORE_NAMESPACE();
namespace kdtree {
namespace packet_internal {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

struct Stack {
  HWY_ALIGN float t_entry[kMaxTraversalStack][kLanes];
  HWY_ALIGN float t_exit[kMaxTraversalStack][kLanes];
  uint32_t node[kMaxTraversalStack];
  uint32_t lanes[kMaxTraversalStack];
};

// Where the kernel's time goes (in-process A/B as below, 7 paired rounds,
// bunny, city2, courtyard-1m, fforest, lost-empire, hairball-small,
// 2026-12-06; tracing time alone, each pass less its replay): traced a second
// time right after the first, a packet costs 0.42-0.56 of its first trace
// (camera pass; shadow pass 0.42-0.62); traced after the AVX3 kernel (the
// same memory, other branch addresses), 0.72-0.84 (shadow 0.66-1.04). So on
// these scenes about a fifth of the first trace waits on memory and a
// further fifth to a third on branch prediction; the vector arithmetic is
// not the bottleneck (the leaf test's rejection computed twice adds only
// 3-10 %). Tried and not kept: prefetching a pushed child's node (T_R
// 0.995-1.012 old over new) and, at each inner node, the first packet of a
// left child that is a leaf (0.994-1.004), against 0.994-1.007 with the same
// code on both sides; packets of 32 rays (two 4x4 blocks, two 16-lane
// vectors descending together): lanes per inner step 13.5 -> 24.3 on bunny,
// inner steps per ray nearly halved, yet the camera pass unchanged there
// (22.2 -> 22.3 ms) and within the noise between processes against Embree's
// packets on city2, courtyard-1m and fforest; the same 32-ray packets with
// each leaf triangle loaded once and tested against both vectors in one
// loop: camera pass 1.01-1.05 of the time of the two vectors' loops one
// after the other. Cycle counters (rdtsc, 2026-12-06, one thread): the leaf
// tests take 54-72 % of the kernel's time on camera packets and 44-62 % on
// shadow packets (bunny, city2, courtyard-1m, lost-empire, hairball-small);
// on bunny a camera packet with live lanes costs about 1,640 cycles in the
// kernel, 1.5 non-empty leaves of about 15 triangle steps at about 50 cycles
// each, and its set-up (LoadLanes, SetUpLanes) 120 cycles; 16-21 % of the
// triangle steps reach FinishLanes. Also not kept: the one-sided choices by
// a conditional move, only "both" by a branch (camera pass 3-8 % slower).
//
// The group's lanes, kV vectors of Lanes(d) (all kLanes of them: one vector
// on AVX-512, two on AVX2, four on SSE4), descending together: a node is
// loaded and decided once for all of them, and the leaf tests run a vector at
// a time. Against tracing each vector on its own (one descent per vector):
// render_bench, sah-packet, 6 scenes (bunny, city, hairball-small, fforest,
// courtyard-1m, teapots), 5 paired rounds, the AVX-512 kernel (one vector,
// unchanged) as the yardstick, old and new binaries alternated twice: the
// AVX2 kernel's T_R per scene went from 0.80-0.89 of the AVX-512 kernel's
// (fforest once 1.00) to 0.84-0.91, SSE4's from 0.62-0.78 to 0.65-0.79:
// 0-7 % faster, none slower beyond noise. (Longer than the project's 80
// lines: the descent, the leaf and the pop share the lanes' intervals and
// masks, which stay in registers only inside one function; the single-ray
// Traverse in traversal.cc is one function for the same reason.)
template <bool kAnyHit, bool kFromEnd, bool kCount, int kV, class D>
HWY_INLINE uint32_t TraceLanes(D d, const KdTree& tree, const PacketRays& p, const Group& g,
                               uint32_t lanes, Hit* best, PacketCounters* counters) {
  PacketCounters* const c = kCount ? counters : nullptr;  // null: no counting code
  using V = hn::Vec<D>;
  constexpr int n = static_cast<int>(hn::MaxLanes(D()));
  static_assert(kV * n == kLanes, "the group's lanes in kV vectors");
  constexpr uint32_t kFull = AllLanes<D>();
  // Vector v holds lanes [v * n, v * n + n).
  V org[kV][3], inv[kV][3], tol[kV][3], t_entry[kV], t_exit[kV], slack[kV];
  for (int v = 0; v < kV; ++v) {
    for (int k = 0; k < 3; ++k) {
      org[v][k] = hn::Load(d, p.org[k] + v * n);
      inv[v][k] = hn::Load(d, p.inv[k] + v * n);
      tol[v][k] = hn::Load(d, p.tol[k] + v * n);
    }
    t_entry[v] = hn::Load(d, p.t_entry + v * n);
    t_exit[v] = hn::Load(d, p.t_exit + v * n);
    slack[v] = hn::Load(d, p.slack + v * n);
  }
  const V inf = hn::Set(d, INFINITY);
  // Shadow rays (any hit from the end; the kernel tests watertight only):
  // the single-ray traversal's tolerance relative to the interval
  // (ray_setup.h IntervalTol), per lane, set at the root and at each pop.
  constexpr bool kRelative = kAnyHit && kFromEnd;
  const auto interval_tol = [&](V a, V b) {
    return hn::Add(hn::Mul(hn::Set(d, ray_setup::kRelTol), hn::Max(hn::Abs(a), hn::Abs(b))),
                   hn::Set(d, ray_setup::kRelTolFloor));
  };
  V rel_tol[kV];
  if (kRelative) {
    for (int v = 0; v < kV; ++v) rel_tol[v] = interval_tol(t_entry[v], t_exit[v]);
  }
  Frames<D> frames[kV];
  for (int v = 0; v < kV; ++v) frames[v] = Frames<D>(d, p, v * n);
  // Each lane's best hit so far (leaf_test-inl.h BestLanes), in vectors: no
  // hit yet, at the ray's tmax. Kept in an array
  // of floats written one at a time, every vector read of the best t after a
  // hit (FinishLanes' tmax, the pop's cull) waited for store-to-load
  // forwarding (in-process A/B, 7 paired rounds, six scenes, 2026-12-06:
  // camera pass 0.982-0.999 of the time, against a control of 0.992-1.012;
  // the whole hit in vectors then 0.950-0.997 of that on eight scenes).
  uint32_t found = 0, index = 0;
  BestLanes<D> bl[kV];
  StartBest(d, p, bl);
  // The lanes with a hit: the answer; closest hit, each gets it in best[].
  const auto finish = [&]() {
    if (!kAnyHit) WriteBest(d, bl, found, best);
    return found;
  };
  const KdNode* nodes = tree.nodes.data();
  Stack stack;
  int top = 0;
  for (;;) {
    const KdNode* node = &nodes[index];
    while (!node->is_leaf()) {
      if (kCount) CountStep(lanes, &c->inner_steps, &c->lanes.inner_visits);
      const int axis = node->axis();
      const V split = hn::Set(d, node->split);
      // The single-ray rules (traversal.cc), per lane.
      V ts[kV];
      uint32_t near_only = 0, far_only = 0;
      V tl[kV];
      for (int v = 0; v < kV; ++v) {
        ts[v] = hn::Mul(hn::Sub(split, org[v][axis]), inv[v][axis]);
        tl[v] = kRelative ? rel_tol[v] : tol[v][axis];
        near_only |= Bits(d, hn::Gt(ts[v], hn::Add(t_exit[v], tl[v]))) << (v * n);
        far_only |= Bits(d, hn::Lt(ts[v], hn::Sub(t_entry[v], tl[v]))) << (v * n);
      }
      near_only &= lanes;
      far_only &= lanes & ~near_only;
      const uint32_t left = index + 1, right = node->index();
      const uint32_t near = g.negative[axis] ? right : left;
      const uint32_t far = g.negative[axis] ? left : right;
      if (far_only == lanes) {
        index = far;
      } else if (near_only == lanes) {
        index = near;
      } else {
        uint32_t both = lanes & ~near_only & ~far_only;
        uint32_t need_near = near_only | both, need_far = far_only | both;
        uint32_t finite = 0;
        for (int v = 0; v < kV; ++v) finite |= Bits(d, hn::Lt(hn::Abs(ts[v]), inf)) << (v * n);
        if ((both & ~finite) != 0) {
          // Parallel to the plane or in it: both children whole within delta
          // of the plane, else the side the origin is on.
          for (uint32_t m = both & ~finite; m != 0; m &= m - 1) {
            const int i = __builtin_ctz(m);
            const float gap = node->split - p.org[axis][i];
            if (!(std::fabs(gap) <= p.delta[i])) {
              const bool to_near = (gap > 0) == (near == left);
              (to_near ? need_far : need_near) &= ~(1u << i);
            }
          }
          both &= finite;
        }
        if (need_near == 0) {
          index = far;
          lanes = need_far;
        } else if (need_far == 0) {
          index = near;
          lanes = need_near;
        } else {
          // Near on [t_entry, ts + tol], far on [ts - tol, t_exit], ts
          // clamped to the interval, for the lanes in `both`. Push one child
          // with its interval and lanes, go on to the other: the far one
          // first with TraversalOptions::from_end, else the near.
          for (int v = 0; v < kV; ++v) {
            const V tc = hn::Min(t_exit[v], hn::Max(t_entry[v], ts[v]));
            const auto clamp = FromBits(d, (both >> (v * n)) & kFull);
            const V near_exit = hn::IfThenElse(clamp, hn::Add(tc, tl[v]), t_exit[v]);
            const V far_entry = hn::IfThenElse(clamp, hn::Sub(tc, tl[v]), t_entry[v]);
            hn::Store(kFromEnd ? t_entry[v] : far_entry, d, stack.t_entry[top] + v * n);
            hn::Store(kFromEnd ? near_exit : t_exit[v], d, stack.t_exit[top] + v * n);
            (kFromEnd ? t_entry[v] : t_exit[v]) = kFromEnd ? far_entry : near_exit;
          }
          stack.node[top] = kFromEnd ? near : far;
          stack.lanes[top++] = kFromEnd ? need_near : need_far;
          if (kCount) ++c->pushes;
          index = kFromEnd ? far : near;
          lanes = kFromEnd ? need_far : need_near;
        }
      }
      node = &nodes[index];
    }
    if (kCount) CountStep(lanes, &c->leaf_steps, &c->lanes.leaf_visits);
    if (node->index() != kEmptyLeaf) {
      for (int v = 0; v < kV; ++v) {
        TestLeafVector<kAnyHit>(d, tree, p, frames[v], g, v * n, node->index(), &lanes, &found,
                                &bl[v], c);
      }
    }
    // Next node: each lane drops it when it starts beyond that lane's best
    // hit plus slack (any hit: lanes with a hit are done).
    for (;;) {
      if (top == 0) return finish();
      --top;
      uint32_t m = stack.lanes[top] & ~(kAnyHit ? found : 0u);
      if (!kAnyHit && (m & found) != 0) {
        uint32_t beyond = 0;
        for (int v = 0; v < kV; ++v) {
          const V limit = hn::Add(bl[v].t, slack[v]);
          beyond |= Bits(d, hn::Gt(hn::Load(d, stack.t_entry[top] + v * n), limit)) << (v * n);
        }
        m &= ~(beyond & found);
      }
      if (m == 0) continue;
      lanes = m;
      index = stack.node[top];
      for (int v = 0; v < kV; ++v) {
        t_entry[v] = hn::Load(d, stack.t_entry[top] + v * n);
        t_exit[v] = hn::Load(d, stack.t_exit[top] + v * n);
        if (kRelative) rel_tol[v] = interval_tol(t_entry[v], t_exit[v]);
      }
      break;
    }
  }
}

template <bool kCount>
uint32_t TraceLanesFor(const KdTree& tree, const PacketRays& p, const Group& g, Search search,
                       Hit* best, PacketCounters* counters) {
  const hn::ScalableTag<float> d;
  constexpr int kV = static_cast<int>(kLanes / hn::MaxLanes(d));
  if (g.lanes == 0) return 0;
  switch (search) {
    case Search::kClosest:
      return TraceLanes<false, false, kCount, kV>(d, tree, p, g, g.lanes, best, counters);
    case Search::kAny:
      return TraceLanes<true, false, kCount, kV>(d, tree, p, g, g.lanes, best, counters);
    case Search::kAnyFromEnd:
      return TraceLanes<true, true, kCount, kV>(d, tree, p, g, g.lanes, best, counters);
  }
  return 0;
}

uint32_t TraceGroupImpl(const KdTree& tree, const PacketRays& p, const Group& g, Search search,
                        Hit* best, PacketCounters* counters) {
  if (counters != nullptr) return TraceLanesFor<true>(tree, p, g, search, best, counters);
  return TraceLanesFor<false>(tree, p, g, search, best, nullptr);
}

const char* KernelTargetImpl() { return hwy::TargetName(HWY_TARGET); }

}  // namespace HWY_NAMESPACE
}  // namespace packet_internal
}  // namespace kdtree
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace kdtree {
namespace packet_internal {

HWY_EXPORT(TraceGroupImpl);
HWY_EXPORT(KernelTargetImpl);

uint32_t TraceGroup(const KdTree& tree, const PacketRays& p, const Group& g, Search search,
                    Hit* best, PacketCounters* counters) {
  return HWY_DYNAMIC_DISPATCH(TraceGroupImpl)(tree, p, g, search, best, counters);
}

const char* KernelTarget() { return HWY_DYNAMIC_DISPATCH(KernelTargetImpl)(); }

std::vector<int64_t> KernelTargets() { return hwy::SupportedAndGeneratedTargets(); }

}  // namespace packet_internal

std::vector<std::string> PacketKernelTargets() {
  std::vector<std::string> names;
  for (const int64_t t : packet_internal::KernelTargets()) names.push_back(hwy::TargetName(t));
  return names;
}

ScopedPacketKernelTarget::ScopedPacketKernelTarget(const std::string& name) {
  for (const int64_t t : packet_internal::KernelTargets()) {
    if (name == hwy::TargetName(t)) {
      hwy::SetSupportedTargetsForTest(t);
      ok_ = true;
      return;
    }
  }
}

ScopedPacketKernelTarget::~ScopedPacketKernelTarget() {
  if (ok_) hwy::SetSupportedTargetsForTest(0);
}

}  // namespace kdtree
#endif  // HWY_ONCE
