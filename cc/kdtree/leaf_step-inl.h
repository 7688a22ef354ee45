// One ray against one leaf's triangles: the leaf step of the single-ray
// traversals, the kd-tree's (traversal.cc) and the BVH over its leaves
// (leaf_bvh_traversal.cc), compiled for the build's static Highway target
// (not dispatched at run time; with -march=native it is the machine's).
//
// A leaf's triangles are stored in packets of four (leaf_layout.h); a step
// tests kStepPackets packets at once, a triangle per lane: two (8 lanes)
// where the static target has 256-bit vectors (--config=opt's -march=native
// on an AVX2 or AVX-512 machine), else one (4 lanes). Against one at a time,
// in one render_bench run (AVX-512 machine, sah-packet, 7 paired rounds): T_R
// 1.06-1.07 on bunny, hairball-small, engine, fforest and armadillo, 1.006 on
// city; the same code on both sides gave 0.99-1.02. The tests run both
// (experiments/test.sh). Four packets a step (16 lanes on AVX-512, each
// coordinate from four 128-bit loads) were within the noise on a Zen 4
// machine (traversal.h, "Tried and not kept") and lost on an Ice Lake
// server (family 6 model 106; 2026-12-07; kd_bvh, the four-packet step
// behind a scratch switch in the same binary, pair_variants, 21 paired
// rounds; bunny, armadillo, lost-empire, city2, teapots, plant-1m,
// courtyard-1m): renders 1.14-1.19 times as long, camera pass 1.17-1.25,
// shadow pass 1.22-1.33.
//
// The per-lane test is the packet kernel's (lane_test-inl.h) with the
// packets' triangles in the lanes: the rejection, then the rest of the
// watertight test in vectors for the lanes with decided signs (bit for bit
// the scalar test's t, u, v), the scalar test for the others; or the fast
// test in vectors (lane_fast_test-inl.h). All lanes are tested against the
// same best.t; Closer then drops a hit beyond one an earlier lane found, as
// the scalar test with that lane's t as tmax would have.
#ifndef KDTREE_CC_KDTREE_LEAF_STEP_INL_H_
#define KDTREE_CC_KDTREE_LEAF_STEP_INL_H_

#include <cstdint>
#include <cstring>

#include "cc/geometry/intersection_mode.h"
#include "cc/geometry/ray.h"
#include "cc/geometry/watertight.h"
#include "cc/kdtree/leaf_layout.h"
#include "cc/kdtree/traversal.h"
#include "hwy/highway.h"
#include "cc/kdtree/lane_fast_test-inl.h"
#include "cc/kdtree/lane_test-inl.h"

namespace kdtree {
namespace leaf_step {

namespace hn = hwy::HWY_NAMESPACE;
namespace lane = packet_internal::HWY_NAMESPACE;
static_assert(HWY_TARGET != HWY_SCALAR, "a leaf packet's four triangles in one vector");
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

// What a leaf step needs of the ray, in every lane, set up once per ray.
// `ray` is the sanitised ray, `wray` its watertight form (ray_setup.h);
// origin_tri is left untested (TraversalOptions::origin_tri; kNoHit: none),
// with the watertight test only.
template <IntersectionMode kMode>
struct LeafRay {
  LeafRay(const Ray& ray, const WatertightRay& w, uint32_t origin_tri)
      : wray(w),
        tmin(ray.tmin),
        behind(ray.tmin >= 0.0f),
        frames(DL(), w, ray.tmin),
        ray_lanes(DL(), ray),
        // kNoHit matches no lane: the ids are stored without kLastPacket's bit.
        skip_id(hn::Set(DU(), kMode == IntersectionMode::kWatertight ? origin_tri : kNoHit)) {
    if (kMode == IntersectionMode::kWatertight) {
      axes.kx = w.kx;
      axes.ky = w.ky;
      axes.kz = w.kz;
    }
  }
  const WatertightRay& wray;
  const float tmin;
  // Triangles wholly behind the origin are rejected in the leaf step too
  // (lane_test-inl.h RejectRays), as the watertight test rejects them.
  const bool behind;
  const lane::Frames<DL> frames;
  const lane::RayLanes<DL> ray_lanes;
  const hn::Vec<DU> skip_id;
  packet_internal::Group axes;  // the fast test's: x, y, z
};

// The leaf whose first packet is `packet` (its packets follow it up to the
// one flagged kLastPacket; soa_end: the end of the tree's packets), against
// *best: a nearer hit (or, for any hit, the first) replaces it. True when
// kAnyHit and a hit was found (the query is answered).
template <bool kAnyHit, bool kCount, IntersectionMode kMode>
HWY_INLINE bool TestLeaf(const LeafRay<kMode>& r, const float* packet, const float* soa_end,
                         Hit* best, TraversalCounters* counters) {
  const DL dl;
  const DU du;
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
    live &= ~static_cast<int>(lane::Bits(du, hn::Eq(clean_ids, r.skip_id)));
    if (kCount) counters->triangle_tests += __builtin_popcount(live);
    const lane::LaneTriangle<DL> step = StepTriangles(dl, r.axes, packet, second);
    lane::LaneShear<DL> s;  // the watertight test's
    if (kMode == IntersectionMode::kWatertight) {
      s = lane::ShearLanes(dl, r.frames, step);
      live &= ~static_cast<int>(lane::RejectRays(dl, r.frames, s, r.behind ? kStepLanes : 0u));
    }
    lane::LaneHits lh;
    if (live != 0 && kMode == IntersectionMode::kWatertight) {
      lane::FinishLanes(dl, r.frames, s, static_cast<uint32_t>(live), hn::Set(dl, best->t), &lh);
    } else if (live != 0) {
      lane::FastLanes(dl, r.ray_lanes, step, r.tmin, best->t, static_cast<uint32_t>(live), &lh);
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
        hit = IntersectTriangleWatertight(r.wray, a, b, c, r.tmin, best->t, &t, &u, &v);
      }
      // Any hit: best holds no hit yet (the first one returns), and a
      // hit with t <= best.t = tmax is always Closer.
      if (hit && (kAnyHit || Closer(t, id[l], *best))) {
        best->tri = id[l];
        best->t = t;
        best->u = u;
        best->v = v;
        if (kAnyHit) return true;
      }
    }
    packet = last ? nullptr : second + kPacketFloats;
  }
  return false;
}

}  // namespace leaf_step
}  // namespace kdtree

#endif  // KDTREE_CC_KDTREE_LEAF_STEP_INL_H_
