// A leaf's triangles against the packet kernel's lanes (ray_packet_kernel.cc),
// per target like it (Highway's per-target include guard): TestLeaf, a
// triangle at a time against every lane, and TestLeafFew, a leaf reached by
// few rays, each ray against a leaf packet's four triangles at once. Both
// test with lane_test-inl.h and record hits in vectors (BestLanes) with the
// single-ray traversal's Closer.
#if defined(KDTREE_CC_KDTREE_LEAF_TEST_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef KDTREE_CC_KDTREE_LEAF_TEST_INL_H_
#undef KDTREE_CC_KDTREE_LEAF_TEST_INL_H_
#else
#define KDTREE_CC_KDTREE_LEAF_TEST_INL_H_
#endif

#include <cstdint>
#include <cstring>

#include "cc/geometry/ray.h"
#include "cc/geometry/watertight.h"
#include "cc/kdtree/lane_test-inl.h"
#include "cc/kdtree/leaf_layout.h"
#include "cc/kdtree/mask_bits-inl.h"
#include "cc/kdtree/packet_rays.h"
#include "cc/kdtree/ray_packet.h"
#include "cc/kdtree/tree.h"
#include "hwy/highway.h"

HWY_BEFORE_NAMESPACE();
namespace kdtree {
namespace packet_internal {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// One more step of a vector of lanes: *steps + 1, *visits + the lanes.
HWY_INLINE void CountStep(uint32_t lanes, uint64_t* steps, uint64_t* visits) {
  ++*steps;
  *visits += static_cast<uint64_t>(__builtin_popcount(lanes));
}

// A vector of lanes' best hits so far, kept in registers: t, u, v and the
// triangle (kNoHit: none yet); the kernel writes them to the caller's Hits
// once, at the end. Against a Hit per lane in memory, recorded by a scalar
// loop over each triangle's hits (Closer, four stores), with the best t
// already in a vector (in-process A/B, 7 paired rounds, 2026-12-06): camera
// pass 0.950-0.997 of the time on eight scenes (bunny, city2, courtyard-1m,
// engine, fforest, hairball-small, lost-empire, teapots), the shadow pass
// within noise.
template <class D>
struct BestLanes {
  hn::Vec<D> t, u, v;
  hn::Vec<hn::RebindToUnsigned<D>> tri;
};

// Each lane's best hit before any leaf, in the kV vectors of a group's
// kLanes lanes: no triangle yet, at the ray's tmax.
template <int kV, class D>
HWY_INLINE void StartBest(D d, const PacketRays& p, BestLanes<D> (&bl)[kV]) {
  constexpr int n = static_cast<int>(hn::MaxLanes(D()));
  const hn::RebindToUnsigned<D> du;
  for (int v = 0; v < kV; ++v) {
    bl[v].t = hn::Load(d, p.tmax + v * n);
    bl[v].u = bl[v].v = hn::Zero(d);
    bl[v].tri = hn::Set(du, kNoHit);
  }
}

// The lanes of `found` (bits) get their best hit in best[i] (the caller's
// Hits; every such lane is below the packet's n); no other entry is
// touched. Tried and not kept (in-process A/B, 7 paired rounds,
// morse-indoor, city2, bunny, lost-empire, morse-kitchen,
// hairball-1m; 2026-12-07): the hits as four vectors of four Hits each
// (StoreInterleaved4), written by masked stores of the found lanes instead
// of the loop below: camera pass 0.981-1.007 of the time, inside the
// noise (the shadow pass, which does not write hits, moved 0.970-0.992).
template <int kV, class D>
HWY_INLINE void WriteBest(D d, const BestLanes<D> (&bl)[kV], uint32_t found, Hit* best) {
  constexpr int n = static_cast<int>(hn::MaxLanes(D()));
  const hn::RebindToUnsigned<D> du;
  HWY_ALIGN float t[kLanes], u[kLanes], w[kLanes];
  HWY_ALIGN uint32_t tri[kLanes];
  for (int v = 0; v < kV; ++v) {
    hn::Store(bl[v].t, d, t + v * n);
    hn::Store(bl[v].u, d, u + v * n);
    hn::Store(bl[v].v, d, w + v * n);
    hn::Store(bl[v].tri, du, tri + v * n);
  }
  for (uint32_t m = found; m != 0; m &= m - 1) {
    const int i = __builtin_ctz(m);
    best[i].tri = tri[i];
    best[i].t = t[i];
    best[i].u = u[i];
    best[i].v = w[i];
  }
}

// The hits `hits` (lanes of the vector at `base`) at t, u, v on triangles
// tri: closest hit, those Closer than the lane's best (ray.h: smaller t, at
// equal t the smaller index); any hit, every one (the lane is done).
template <bool kAnyHit, class D>
HWY_INLINE void RecordLanes(D d, uint32_t hits, hn::Vec<D> t, hn::Vec<D> u, hn::Vec<D> v,
                            hn::Vec<hn::RebindToUnsigned<D>> tri, int base, BestLanes<D>* b,
                            uint32_t* lanes, uint32_t* found) {
  const hn::RebindToUnsigned<D> du;
  uint32_t take = hits;
  if (!kAnyHit) {
    const auto closer = hn::Or(hn::Lt(t, b->t),
                               hn::And(hn::Eq(t, b->t), hn::RebindMask(d, hn::Lt(tri, b->tri))));
    take &= Bits(d, closer);
  }
  if (take == 0) return;
  const auto m = FromBits(d, take);
  b->t = hn::IfThenElse(m, t, b->t);
  b->u = hn::IfThenElse(m, u, b->u);
  b->v = hn::IfThenElse(m, v, b->v);
  b->tri = hn::IfThenElse(FromBits(du, take), tri, b->tri);
  *found |= take << base;
  if (kAnyHit) *lanes &= ~(take << base);
}

// RecordLanes for one lane i.
template <bool kAnyHit, class D>
HWY_INLINE void RecordLane(D d, int i, float t, float u, float v, uint32_t tri, int base,
                           BestLanes<D>* b, uint32_t* lanes, uint32_t* found) {
  const hn::RebindToUnsigned<D> du;
  RecordLanes<kAnyHit>(d, 1u << i, hn::Set(d, t), hn::Set(d, u), hn::Set(d, v), hn::Set(du, tri),
                       base, b, lanes, found);
}

// IntersectTriangleWatertight itself for lane i of the vector at `base` and
// triangle l of the leaf packet, with the lane's best t as tmax; records a
// hit.
template <bool kAnyHit, class D>
HWY_INLINE void ScalarTest(D d, const PacketRays& p, const Group& g, const float* packet, int l,
                           uint32_t tri, int base, int i, BestLanes<D>* b, uint32_t* lanes,
                           uint32_t* found) {
  const size_t r = static_cast<size_t>(base + i);
  Vec3 a, bb, c;
  PacketTriangle(packet, l, &a, &bb, &c);
  float t, u, v;
  const WatertightRay w = LaneRay(p, g.kx, g.ky, g.kz, static_cast<int>(r));
  if (IntersectTriangleWatertight(w, a, bb, c, p.tmin[r], hn::ExtractLane(b->t, i), &t, &u, &v)) {
    RecordLane<kAnyHit>(d, i, t, u, v, tri, base, b, lanes, found);
  }
}

// The leaf's triangles against the live lanes of the vector at `base`, a
// triangle at a time; `lanes` and `found` hold the whole group's bits (any
// hit: a lane with a hit is done). Tried and not kept (in-process A/B, the
// new code on AVX3_DL against the old on AVX3, 7 paired rounds, 2026-12-06):
// prefetching the next leaf packet (T_R 0.995-1.015 old over new, the
// control 0.998-1.009), and for lanes sharing their origin (camera packets)
// moving the triangle to it once in scalars (primary pass 2-9 % slower: the
// broadcasts cost more than the vector subtractions they save); and the
// rejection of a leaf packet's four triangles computed before any branch on
// its result (T_R 0.995-1.007 old over new on six scenes: no change). Nor
// (the BVH's packets, 7 paired rounds, city2, morse-indoor, lost-empire,
// hairball-small, hairball-1m, courtyard-1m, bunny; 2026-12-07) a cull of a
// leaf packet's triangles for the whole group before the lanes' tests, in
// one 4-wide pass per packet: each vertex's sheared x and y bounded over the
// group's intervals of origins and shears (exact: rounding is monotone, as
// in slot_filter-inl.h), a triangle with every vertex on one side of zero
// missed by every lane. It culled 56-69 % of the triangle steps on city2,
// lost-empire and bunny, and renders took 1.02-1.15 times as long (camera
// pass 1.01-1.19): a triangle every lane rejects costs the lanes' test
// little beside the cull's 4-wide pass. FinishLanes is not where the leaf's
// time goes either: run twice on each of TestLeaf's calls, it added 0.4-0.75
// ms to camera passes of 7.8-12.4 ms (city2, lost-empire, bunny; nothing
// measurable on shadow passes or hairball-1m). Nor did moving the step's
// rest (FinishLanes, the records, the scalar tests) out of line, the shear
// computed again there, so that the loop need not keep the shear (GCC
// stores a dozen of its vectors to the stack on every step, for the rare
// path): kd_bvh_packet's camera pass 1.00-1.04 times as long, its shadow
// pass 1.00-1.03 (pair_variants, 21 paired rounds, bunny, armadillo,
// lost-empire, city2, courtyard-1m, hairball-1m; 2026-12-07).
template <bool kAnyHit, class D>
HWY_INLINE void TestLeaf(D d, const KdTree& tree, const PacketRays& p, const Frames<D>& f,
                         const Group& g, int base, uint32_t first, uint32_t* lanes,
                         uint32_t* found, BestLanes<D>* b, PacketCounters* c) {
  const hn::RebindToUnsigned<D> du;
  constexpr uint32_t kFull = AllLanes<D>();
  const bool origins = p.has_origins;
  const uint32_t behind = (p.behind >> base) & kFull;
  const float* packet = tree.leaf_soa.data() + static_cast<size_t>(first) * kPacketFloats;
  for (;;) {
    uint32_t id[kPacketLanes];
    std::memcpy(id, packet + kPacketIds, sizeof(id));
    const bool last = (id[0] & kLastPacket) != 0;
    id[0] &= ~kLastPacket;
    for (int l = 0; l < kPacketLanes; ++l) {
      const uint32_t sub = (*lanes >> base) & kFull;
      if (sub == 0 || id[l] == kPadLane) break;  // pads only follow a leaf's last triangle
      const LaneShear<D> s = ShearLanes(d, f, BroadcastTriangle(d, g, packet, l));
      uint32_t rays = sub & ~RejectRays(d, f, s, behind & sub);
      const uint32_t own =
          origins ? Bits(du, hn::Eq(hn::Load(du, p.origin + base), hn::Set(du, id[l]))) : 0;
      // Unconditional: a branch on rays != 0 first mispredicts often on
      // shadow rays, most of whose tests reject every ray (paired rounds on
      // 8 scenes: shadow pass 1-10 % faster without it and TestLeafFew's).
      rays &= ~own;
      if (c != nullptr) CountStep(sub & ~own, &c->triangle_steps, &c->lanes.triangle_tests);
      if (rays == 0) continue;
      LaneHits lh;
      LaneHitVecs<D> hv;
      FinishLanes(d, f, s, rays, b->t, &lh, &hv);
      RecordLanes<kAnyHit>(d, lh.hit, hv.t, hv.u, hv.v, hn::Set(du, id[l]), base, b, lanes, found);
      for (uint32_t m = lh.scalar; m != 0; m &= m - 1) {
        ScalarTest<kAnyHit>(d, p, g, packet, l, id[l], base, __builtin_ctz(m), b, lanes, found);
      }
    }
    if (last || ((*lanes >> base) & kFull) == 0) return;
    packet += kPacketFloats;
  }
}

// The few-ray path (TestLeafFew), on targets of at least kPacketLanes lanes.
#if HWY_TARGET != HWY_SCALAR
// TestLeafFew's hits (lanes of `hits`; block k of kPacketLanes lanes holds
// ray `ray[k]` against the leaf packet's triangles, tri): per block, the
// Closer of its hits (ray.h's order, by two exchanges within the block), then
// recorded for the block's ray (`to_ray`: the block's first lane, for each
// ray's lane).
template <bool kAnyHit, class D>
HWY_INLINE void RecordBlocks(D d, uint32_t hits, const LaneHitVecs<D>& hv,
                             hn::Vec<hn::RebindToUnsigned<D>> tri, const int* ray, int rays_in,
                             const int32_t* to_ray, int base, BestLanes<D>* b, uint32_t* lanes,
                             uint32_t* found) {
  const hn::RebindToUnsigned<D> du;
  using V = hn::Vec<D>;
  using VU = hn::Vec<decltype(du)>;
  V t = hn::IfThenElse(FromBits(d, hits), hv.t, hn::Set(d, INFINITY)), u = hv.u, v = hv.v;
  VU id = hn::IfThenElse(FromBits(du, hits), tri, hn::Set(du, ~0u));
  const auto keep_closer = [&](V t2, V u2, V v2, VU id2) {
    const auto better =
        hn::Or(hn::Lt(t2, t), hn::And(hn::Eq(t2, t), hn::RebindMask(d, hn::Lt(id2, id))));
    t = hn::IfThenElse(better, t2, t);
    u = hn::IfThenElse(better, u2, u);
    v = hn::IfThenElse(better, v2, v);
    id = hn::IfThenElse(hn::RebindMask(du, better), id2, id);
  };
  keep_closer(hn::Shuffle2301(t), hn::Shuffle2301(u), hn::Shuffle2301(v), hn::Shuffle2301(id));
  keep_closer(hn::Shuffle1032(t), hn::Shuffle1032(u), hn::Shuffle1032(v), hn::Shuffle1032(id));
  constexpr uint32_t kBlock = (1u << kPacketLanes) - 1;
  uint32_t take = 0;
  for (int k = 0; k < rays_in; ++k) {
    if ((hits >> (k * kPacketLanes)) & kBlock) take |= 1u << ray[k];
  }
  const auto idx = hn::SetTableIndices(d, to_ray);
  RecordLanes<kAnyHit>(d, take, hn::TableLookupLanes(t, idx), hn::TableLookupLanes(u, idx),
                       hn::TableLookupLanes(v, idx),
                       hn::TableLookupLanes(id, hn::SetTableIndices(du, to_ray)), base, b, lanes,
                       found);
}

// TestLeaf for the lanes `set` of the vector at `base` (bits relative to
// it), at most Lanes(d) / kPacketLanes of them: each block of kPacketLanes
// vector lanes holds one ray (its frame permuted there) against the leaf
// packet's kPacketLanes triangles, so a leaf packet takes one vector test
// instead of one per triangle. The triangles of a leaf packet are tested at
// once, not one after the other: each ray takes the Closer of its block's
// hits (RecordBlocks), and the rare lanes left to the scalar test follow one
// by one, so every ray ends with the same closest hit (any hit: a ray with a
// hit is done). The block's choice in vectors, against recording the hits
// lane by lane (in-process A/B, 7 paired rounds, eight scenes, 2026-12-06):
// camera pass 0.970-0.999 of the time, shadow 0.966-1.004, at the edge of
// the control's 0.992-1.012 and 0.969-0.991.
template <bool kAnyHit, class D>
HWY_INLINE void TestLeafFew(D d, const KdTree& tree, const PacketRays& p, const Frames<D>& f,
                            const Group& g, int base, uint32_t first, uint32_t set,
                            uint32_t* lanes, uint32_t* found, BestLanes<D>* b,
                            PacketCounters* c) {
  const hn::RebindToUnsigned<D> du;
  const size_t n = hn::Lanes(d);
  int ray[kLanes / kPacketLanes];
  int rays_in = 0;
  for (uint32_t m = set; m != 0; m &= m - 1) ray[rays_in++] = __builtin_ctz(m);
  if (rays_in == 0) __builtin_unreachable();
  HWY_ALIGN int32_t index[kLanes];
  for (size_t j = 0; j < n; ++j) {
    const int k = static_cast<int>(j / kPacketLanes);
    index[j] = ray[k < rays_in ? k : rays_in - 1];
  }
  constexpr uint32_t kBlock = (1u << kPacketLanes) - 1;
  uint32_t behind = 0;
  for (int k = 0; k < rays_in; ++k) {
    if ((p.behind >> (base + ray[k])) & 1) behind |= kBlock << (k * kPacketLanes);
  }
  HWY_ALIGN int32_t to_ray[kLanes] = {0};
  for (int k = 0; k < rays_in; ++k) to_ray[ray[k]] = k * kPacketLanes;
  const auto perm = hn::SetTableIndices(d, index);
  const Frames<D> pf = f.Permuted(perm);
  const auto origin =
      hn::TableLookupLanes(hn::Load(du, p.origin + base), hn::SetTableIndices(du, index));
  HWY_ALIGN static constexpr uint32_t kIdMask[kPacketLanes] = {~kLastPacket, ~0u, ~0u, ~0u};
  const float* packet = tree.leaf_soa.data() + static_cast<size_t>(first) * kPacketFloats;
  for (;;) {
    uint32_t id[kPacketLanes];
    std::memcpy(id, packet + kPacketIds, sizeof(id));
    const bool last = (id[0] & kLastPacket) != 0;
    id[0] &= ~kLastPacket;
    // The indices as a vector straight from the packet: a 16-byte load of
    // `id` after its scalar stores waits for them (store-to-load forwarding
    // fails on a load spanning several stores), which perf showed as two of
    // the kernel's hottest spots; read from the packet, they are gone. Time
    // (in-process A/B, 7 paired rounds, six scenes, 2026-12-06): shadow pass
    // 0.949-0.986 of the old time, camera 0.976-1.033, but the control (the
    // same code on both sides) gave shadow 0.969-0.991: within noise.
    const auto ids = hn::And(hn::BitCast(du, hn::LoadDup128(d, packet + kPacketIds)),
                             hn::LoadDup128(du, kIdMask));
    uint32_t live = 0;  // the blocks of rays still looking (any hit: some are done)
    for (int k = 0; k < rays_in; ++k) {
      if ((*lanes >> (base + ray[k])) & 1) live |= kBlock << (k * kPacketLanes);
    }
    live &= ~Bits(du, hn::Eq(ids, hn::Set(du, kPadLane)));
    const LaneShear<D> s = ShearLanes(d, pf, RepeatTriangles(d, g, packet));
    uint32_t rays = live & ~RejectRays(d, pf, s, behind & live);
    const uint32_t own = p.has_origins ? Bits(du, hn::Eq(origin, ids)) : 0;
    rays &= ~own;  // no branch on rays (TestLeaf)
    if (c != nullptr) CountStep(live & ~own, &c->triangle_steps, &c->lanes.triangle_tests);
    if (rays != 0) {
      LaneHits lh;
      LaneHitVecs<D> hv;
      FinishLanes(d, pf, s, rays, hn::TableLookupLanes(b->t, perm), &lh, &hv);
      if (lh.hit != 0) {
        RecordBlocks<kAnyHit>(d, lh.hit, hv, ids, ray, rays_in, to_ray, base, b, lanes, found);
      }
      for (uint32_t m = lh.scalar; m != 0; m &= m - 1) {
        const int j = __builtin_ctz(m);
        const int i = index[j], l = j % kPacketLanes;
        if (kAnyHit && !((*lanes >> (base + i)) & 1)) continue;  // found already
        ScalarTest<kAnyHit>(d, p, g, packet, l, id[l], base, i, b, lanes, found);
      }
    }
    if (last || ((*lanes >> base) & set) == 0) return;
    packet += kPacketFloats;
  }
}
#endif  // HWY_TARGET != HWY_SCALAR

// Up to how many vectors of TestLeafFew (each Lanes / kPacketLanes rays) a
// leaf gets instead of TestLeaf's kPacketLanes vectors per leaf packet: 2,
// so rays up to half the lanes (paired rounds against 1: T_R 1.025 bunny,
// 1.002 city, 1.041 hairball-small; 3 was no better).
constexpr int kFewSets = 2;


// The lanes of vector [base, base + Lanes(d)) that reach a leaf, against its
// triangles: a triangle against the lanes (TestLeaf) or, where the lanes
// diverged and few reach it, each ray against a leaf packet's four triangles
// at once (TestLeafFew). `lanes` and `found` hold the whole group's bits.
template <bool kAnyHit, class D>
HWY_INLINE void TestLeafVector(D d, const KdTree& tree, const PacketRays& p,
                               const Frames<D>& frames, const Group& g, int base, uint32_t leaf,
                               uint32_t* lanes, uint32_t* found, BestLanes<D>* b,
                               PacketCounters* c) {
  constexpr int n = static_cast<int>(hn::MaxLanes(D()));
  const uint32_t sub = (*lanes >> base) & AllLanes<D>();
  if (sub == 0) return;
#if HWY_TARGET != HWY_SCALAR
  // A leaf reached by few rays is tested a ray per block of kPacketLanes
  // lanes (TestLeafFew), on targets of at least kPacketLanes lanes.
  if (__builtin_popcount(sub) * kPacketLanes <= kFewSets * n) {
    // Rays are independent: a few at a time, each set as many as fit.
    constexpr int kPerSet = n / kPacketLanes;
    for (uint32_t rest = sub; rest != 0;) {
      uint32_t set = 0;
      for (int k = 0; k < kPerSet && rest != 0; ++k) {
        set |= rest & -rest;
        rest &= rest - 1;
      }
      TestLeafFew<kAnyHit>(d, tree, p, frames, g, base, leaf, set, lanes, found, b, c);
    }
    return;
  }
#else
  (void)n;
#endif
  TestLeaf<kAnyHit>(d, tree, p, frames, g, base, leaf, lanes, found, b, c);
}

}  // namespace HWY_NAMESPACE
}  // namespace packet_internal
}  // namespace kdtree
HWY_AFTER_NAMESPACE();

#endif  // KDTREE_CC_KDTREE_LEAF_TEST_INL_H_
