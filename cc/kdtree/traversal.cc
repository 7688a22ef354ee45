#include "cc/kdtree/traversal.h"

#include <cassert>
#include <cmath>
#include <cstring>

#include "cc/geometry/watertight.h"
#include "cc/kdtree/leaf_layout.h"
#include "cc/kdtree/ray_setup.h"

#include <immintrin.h>

#include "hwy/highway.h"
// For the static target (this file is not dispatched at run time; with
// -march=native it is the machine's).
#include "cc/kdtree/lane_fast_test-inl.h"
#include "cc/kdtree/lane_test-inl.h"

namespace kdtree {

namespace {
namespace hn = hwy::HWY_NAMESPACE;
namespace lane = packet_internal::HWY_NAMESPACE;
static_assert(HWY_TARGET != HWY_SCALAR, "a leaf packet's four triangles in one vector");
// A leaf step tests kStepPackets leaf packets at once, a triangle per lane:
// two (8 lanes) where the build's static target has 256-bit vectors
// (--config=opt's -march=native on an AVX2 or AVX-512 machine), else one (4
// lanes). Against one at a time, in one render_bench run (AVX-512 machine,
// sah-packet, 7 paired rounds): T_R 1.06-1.07 on bunny, hairball-small,
// engine, fforest and armadillo, 1.006 on city; the same code on both sides
// gave 0.99-1.02. The tests run both (experiments/test.sh).
using DL = hn::CappedTag<float, 2 * kPacketLanes>;
using DU = hn::RebindToUnsigned<DL>;
constexpr int kStepPackets = HWY_MAX_BYTES >= 32 ? 2 : 1;
static_assert(kStepPackets * kPacketLanes == hn::MaxLanes(DL()), "a triangle per lane");
constexpr uint32_t kStepLanes = (1u << (kStepPackets * kPacketLanes)) - 1;

// The triangles of packets p0 and p1 (kStepPackets of them) in the lanes.
HWY_INLINE lane::LaneTriangle<DL> StepTriangles(DL d, const packet_internal::Group& g,
                                                const float* p0, const float* p1) {
  if constexpr (kStepPackets == 1) {
    (void)p1;
    return lane::RepeatTriangles(d, g, p0);
  } else {
    const hn::Half<DL> dh;
    const auto two = [&](int offset) {
      return hn::Combine(d, hn::LoadU(dh, p1 + offset), hn::LoadU(dh, p0 + offset));
    };
    lane::LaneTriangle<DL> t;
    for (int v = 0; v < 3; ++v) {
      t.x[v] = two((3 * v + g.kx) * kPacketLanes);
      t.y[v] = two((3 * v + g.ky) * kPacketLanes);
      t.z[v] = two((3 * v + g.kz) * kPacketLanes);
    }
    return t;
  }
}

// Their triangle indices (leaf_layout.h: the bit patterns after the vertices).
HWY_INLINE hn::Vec<DU> StepIds(DU du, const float* p0, const float* p1) {
  const uint32_t* i0 = reinterpret_cast<const uint32_t*>(p0 + kPacketIds);
  if constexpr (kStepPackets == 1) {
    (void)p1;
    return hn::LoadU(du, i0);
  } else {
    const hn::Half<DU> dh;
    return hn::Combine(du, hn::LoadU(dh, reinterpret_cast<const uint32_t*>(p1 + kPacketIds)),
                       hn::LoadU(dh, i0));
  }
}

struct StackEntry {
  uint32_t node;
  float t_entry, t_exit;
  float interval_tol;  // IntervalTol(t_entry, t_exit), shadow rays only
};

// The single-ray traversal: set-up, then a loop of three parts (the descent
// to a leaf, the leaf's triangles, the pop of the next node). Longer than the
// project's 80 lines on purpose: the three parts share the ray's set-up, the
// interval, the stack and the best hit, a dozen values the loop
// keeps in registers; as separate functions they would take them by
// reference, which keeps them in memory unless every call is inlined. The
// packet kernel's TraceLanes (ray_packet_kernel.cc) is one function for the
// same reason.
template <bool kAnyHit, bool kCount, IntersectionMode kMode, bool kFromEnd>
Hit Traverse(const KdTree& tree, const Ray& input, uint32_t origin_tri,
             TraversalCounters* counters) {
  Hit best;
  if (kCount) ++counters->rays;
  Ray ray = LoadRay(input);  // not a wide copy (ray.h)
  if (tree.nodes.empty() || !tree.bounds.Valid()) return best;
  // SanitizeRay, then the reciprocal direction, tolerances, the padded root
  // interval, the slack and the watertight ray (ray_setup.h; see the
  // robustness notes in traversal.h).
  RaySetup setup;
  if (!SanitizeAndSetUpRay(&ray, tree.bounds, &setup)) return best;
  const float* const org = setup.org;
  const float* const inv = setup.inv;
  const float* const tol = setup.tol;
  const bool* const negative = setup.negative;
  const float delta = setup.delta;
  float t_entry = setup.t_entry, t_exit = setup.t_exit;
  // Shadow rays (any hit from the end, watertight test) thicken the planes
  // by a tolerance relative to the interval instead of tol (traversal.h,
  // "Robustness"): computed here and for each pushed node, kept in the
  // stack entry, so a pop does not wait for it.
  constexpr bool kRelative = kAnyHit && kFromEnd && kMode == IntersectionMode::kWatertight;
  float interval_tol = kRelative ? ray_setup::IntervalTol(t_entry, t_exit) : 0.0f;
  best.t = ray.tmax;
  const float slack = setup.slack;
  const WatertightRay& wray = setup.wray;
  // Triangles wholly behind the origin are rejected in the leaf step too
  // (lane_test-inl.h RejectRays), as the watertight test rejects them.
  const bool behind = ray.tmin >= 0.0f;
  // The ray in every lane of a leaf step (lane_test-inl.h).
  const DL dl;
  const DU du;
  const lane::Frames<DL> frames(dl, wray, ray.tmin);
  packet_internal::Group axes;  // the fast test's: x, y, z
  if (kMode == IntersectionMode::kWatertight) {
    axes.kx = wray.kx;
    axes.ky = wray.ky;
    axes.kz = wray.kz;
  }
  const lane::RayLanes<DL> ray_lanes(dl, ray);
  // The origin triangle (TraversalOptions::origin_tri), watertight only
  // (kNoHit matches no lane: the ids are stored without kLastPacket's bit).
  if (kMode != IntersectionMode::kWatertight) origin_tri = kNoHit;
  const hn::Vec<DU> skip_id = hn::Set(du, origin_tri);
  StackEntry stack[kMaxTraversalStack];
  int top = 0;
  // The nodes; a leaf points at its packets (leaf_layout.h).
  const KdNode* nodes = tree.nodes.data();
  const float* soa = tree.leaf_soa.data();
  const float* soa_end = soa + tree.leaf_soa.size();
  uint32_t index = 0;
  for (;;) {
    const KdNode* node = &nodes[index];
    while (!node->is_leaf()) {
      if (kCount) ++counters->inner_visits;
      const int axis = node->axis();
      const float t_split = (node->split - org[axis]) * inv[axis];
      const uint32_t left = index + 1, right = node->index();
      const uint32_t near = negative[axis] ? right : left;
      const uint32_t far = negative[axis] ? left : right;
      // A child is skipped only when the plane (thickened by the tolerance) is
      // clearly outside the interval.
      const float t_tol = kRelative ? interval_tol : tol[axis];
      if (t_split > t_exit + t_tol) {
        index = near;
      } else if (t_split < t_entry - t_tol) {
        index = far;
      } else if (std::fabs(t_split) < INFINITY) {
        // Clamp to [t_entry, t_exit] (no NaN here: plain comparisons).
        const float lo = t_split < t_entry ? t_entry : t_split;
        const float ts = lo > t_exit ? t_exit : lo;
        assert(top < kMaxTraversalStack);
        if (kFromEnd) {  // TraversalOptions::from_end: the far child first
          const float near_exit = ts + t_tol;
          stack[top++] = StackEntry{near, t_entry, near_exit,
                                    kRelative ? ray_setup::IntervalTol(t_entry, near_exit) : 0.0f};
          index = far;
          t_entry = ts - t_tol;
        } else {
          stack[top++] = StackEntry{far, ts - t_tol, t_exit, 0.0f};
          _mm_prefetch(reinterpret_cast<const char*>(&nodes[far]), _MM_HINT_T0);
          index = near;
          t_exit = ts + t_tol;
        }
      } else {
        // Parallel to the plane (t_split infinite) or in it (NaN): both
        // children whole when the origin is within delta of the plane, else
        // the side the origin is on.
        const float gap = node->split - org[axis];
        if (std::fabs(gap) <= delta) {
          assert(top < kMaxTraversalStack);
          stack[top++] = StackEntry{kFromEnd ? near : far, t_entry, t_exit,
                                    kRelative ? ray_setup::IntervalTol(t_entry, t_exit) : 0.0f};
          index = kFromEnd ? far : near;
        } else {
          index = gap > 0 ? left : right;
        }
      }
      node = &nodes[index];
    }
    if (kCount) ++counters->leaf_visits;
    const uint32_t first = node->index();
    const float* packet =
        first == kEmptyLeaf ? nullptr : soa + static_cast<size_t>(first) * kPacketFloats;
    while (packet != nullptr) {
      // This step's packets: `packet` and, when a step takes two, the next
      // one in memory, whose lanes are masked off when `packet` ends the
      // leaf (`only`). Its address does not wait for `packet`'s ids, so
      // the two packets' cache lines are requested at once; choosing it by
      // the ids (a conditional move) made every second packet wait for the
      // first one's last line. render_bench, sah-packet, Embree's single
      // rays over kd_origin, 6 processes each, old and new alternated:
      // hairball-1m 0.53-0.58 -> 0.58-0.63; bunny, city, rungholt-1m,
      // courtyard-1m, fforest and hairball-small within noise.
      const float* next = packet + kPacketFloats;
      const float* second = kStepPackets == 1 || next == soa_end ? packet : next;
      uint32_t first_id;
      std::memcpy(&first_id, packet + kPacketIds, sizeof(first_id));
      const bool ends = (first_id & kLastPacket) != 0;  // `packet` ends the leaf
      const bool only = kStepPackets == 1 || ends;
      const hn::Vec<DU> ids = StepIds(du, packet, second);
      const hn::Vec<DU> clean_ids = hn::And(ids, hn::Set(du, ~kLastPacket));
      HWY_ALIGN uint32_t id[kStepPackets * kPacketLanes];
      hn::Store(clean_ids, du, id);
      // Lanes holding a triangle (not kPadLane) of this leaf.
      int live = static_cast<int>(~lane::Bits(du, hn::Eq(ids, hn::Set(du, kPadLane))) &
                                  (only ? (1u << kPacketLanes) - 1 : kStepLanes));
      uint32_t last_id;
      std::memcpy(&last_id, second + kPacketIds, sizeof(last_id));
      const bool last = ends || (last_id & kLastPacket) != 0;
      live &= ~static_cast<int>(lane::Bits(du, hn::Eq(clean_ids, skip_id)));
      if (kCount) counters->triangle_tests += __builtin_popcount(live);
      // The packet kernel's per-lane test (lane_test-inl.h) with the
      // packets' triangles in the lanes: the rejection, then the rest of
      // the test in vectors for the lanes with decided signs (bit for bit
      // the scalar test's t, u, v), the scalar test for the others; or the
      // fast test in vectors (lane_fast_test-inl.h). All lanes are tested
      // against the same best.t; Closer then drops a hit beyond one an
      // earlier lane found, as the scalar test with that lane's t as tmax
      // would have.
      const lane::LaneTriangle<DL> step = StepTriangles(dl, axes, packet, second);
      lane::LaneShear<DL> s;  // the watertight test's
      if (kMode == IntersectionMode::kWatertight) {
        s = lane::ShearLanes(dl, frames, step);
        live &= ~static_cast<int>(lane::RejectRays(dl, frames, s, behind ? kStepLanes : 0u));
      }
      lane::LaneHits lh;
      if (live != 0 && kMode == IntersectionMode::kWatertight) {
        lane::FinishLanes(dl, frames, s, static_cast<uint32_t>(live), hn::Set(dl, best.t), &lh);
      } else if (live != 0) {
        lane::FastLanes(dl, ray_lanes, step, ray.tmin, best.t, static_cast<uint32_t>(live), &lh);
      }
      for (uint32_t m = lh.hit | lh.scalar; m != 0; m &= m - 1) {
        const int l = __builtin_ctz(m);
        float t, u, v;
        bool hit;
        if ((lh.hit >> l) & 1) {
          t = lh.t[l];
          u = lh.u[l];
          v = lh.v[l];
          hit = true;
        } else {
          Vec3 a, b, c;
          PacketTriangle(l < kPacketLanes ? packet : second, l % kPacketLanes, &a, &b, &c);
          hit = IntersectTriangleWatertight(wray, a, b, c, ray.tmin, best.t, &t, &u, &v);
        }
        // Any hit: best holds no hit yet (the first one returns), and a
        // hit with t <= best.t = tmax is always Closer.
        if (hit && (kAnyHit || Closer(t, id[l], best))) {
          best.tri = id[l];
          best.t = t;
          best.u = u;
          best.v = v;
          if (kAnyHit) return best;
        }
      }
      packet = last ? nullptr : second + kPacketFloats;
    }
    // Next node. A node that starts beyond the best hit (with the slack for
    // the rounding of triangle distances) cannot hold a nearer one or a tie.
    for (;;) {
      if (top == 0) {
        if (!best.hit()) best.t = INFINITY;
        return best;
      }
      const StackEntry& e = stack[--top];
      if (!kAnyHit && best.hit() && e.t_entry > best.t + slack) continue;
      index = e.node;
      t_entry = e.t_entry;
      t_exit = e.t_exit;
      if (kRelative) interval_tol = e.interval_tol;
      break;
    }
  }
}

// The order matters to any-hit queries only (TraversalOptions::from_end).
template <bool kAnyHit, bool kCount, IntersectionMode kMode>
Hit DispatchOrder(const KdTree& tree, const Ray& ray, const TraversalOptions& options,
                  TraversalCounters* counters) {
  return kAnyHit && options.from_end
             ? Traverse<kAnyHit, kCount, kMode, kAnyHit>(tree, ray, options.origin_tri, counters)
             : Traverse<kAnyHit, kCount, kMode, false>(tree, ray, options.origin_tri, counters);
}

template <bool kAnyHit>
Hit Dispatch(const KdTree& tree, const Ray& ray, TraversalCounters* counters,
             const TraversalOptions& options) {
  if (options.mode == IntersectionMode::kWatertight) {
    return counters != nullptr
               ? DispatchOrder<kAnyHit, true, IntersectionMode::kWatertight>(tree, ray, options,
                                                                            counters)
               : DispatchOrder<kAnyHit, false, IntersectionMode::kWatertight>(tree, ray, options,
                                                                             nullptr);
  }
  return counters != nullptr
             ? DispatchOrder<kAnyHit, true, IntersectionMode::kFast>(tree, ray, options, counters)
             : DispatchOrder<kAnyHit, false, IntersectionMode::kFast>(tree, ray, options, nullptr);
}

}  // namespace

Hit Intersect(const KdTree& tree, const Ray& ray, const TraversalOptions& options,
              TraversalCounters* counters) {
  return Dispatch<false>(tree, ray, counters, options);
}
bool Occluded(const KdTree& tree, const Ray& ray, const TraversalOptions& options,
              TraversalCounters* counters) {
  return Dispatch<true>(tree, ray, counters, options).hit();
}

}  // namespace kdtree
