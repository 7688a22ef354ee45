// A leaf's triangles against the packet kernel's lanes (ray_packet_kernel.cc),
// per target like it (Highway's per-target include guard): TestLeaf, a
// triangle at a time against every lane, and TestLeafFew, a leaf reached by
// few rays, each ray against a leaf packet's four triangles at once. Both
// test with lane_test-inl.h and record hits with the single-ray traversal's
// Closer.
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

// Lane i's hit on triangle `tri` at t (u, v), if it is the closest so far
// (any hit: the lane is done). Whether it was recorded: the caller then sets
// lane i of its best t's vector (closest hit).
template <bool kAnyHit>
HWY_INLINE bool Record(int i, uint32_t tri, float t, float u, float v, Hit* h, uint32_t* lanes,
                       uint32_t* found) {
  if (!kAnyHit && !Closer(t, tri, *h)) return false;
  h->tri = tri;
  h->t = t;
  h->u = u;
  h->v = v;
  *found |= 1u << i;
  if (kAnyHit) *lanes &= ~(1u << i);
  return true;
}

// Lane i of *bt set to t.
template <class D>
HWY_INLINE void SetLane(D d, int i, float t, hn::Vec<D>* bt) {
  *bt = hn::IfThenElse(FromBits(d, 1u << i), hn::Set(d, t), *bt);
}

// IntersectTriangleWatertight itself for ray r of the packet and triangle l
// of the leaf packet (with the ray's best hit so far as tmax); records a hit
// for lane i (r - base), and says whether it did (Record).
template <bool kAnyHit>
HWY_INLINE bool ScalarTest(const PacketRays& p, const Group& g, const float* packet, int l,
                           uint32_t tri, size_t base, int i, uint32_t* lanes, uint32_t* found,
                           Hit* best) {
  const size_t r = base + i;
  Vec3 a, b, c;
  PacketTriangle(packet, l, &a, &b, &c);
  float t, u, v;
  const WatertightRay w = LaneRay(p, g.kx, g.ky, g.kz, static_cast<int>(r));
  if (IntersectTriangleWatertight(w, a, b, c, p.tmin[r], best[r].t, &t, &u, &v)) {
    return Record<kAnyHit>(i, tri, t, u, v, &best[r], lanes, found);
  }
  return false;
}

// The lanes of `lanes` the leaf's triangles are tested against; updates best
// and *bt, the lanes' best t (closest hit), or `lanes` and *found (any hit: a
// lane with a hit is done). Tried and not kept (in-process A/B, the new code on AVX3_DL
// against the old on AVX3, 7 paired rounds, 2026-12-06): prefetching the next
// leaf packet (T_R 0.995-1.015 old over new, the control 0.998-1.009), and for
// lanes sharing their origin (camera packets) moving the triangle to it once
// in scalars (primary pass 2-9 % slower: the broadcasts cost more than the
// vector subtractions they save); and the rejection of a leaf packet's four
// triangles computed before any branch on its result (T_R 0.995-1.007 old
// over new on six scenes: no change).
template <bool kAnyHit, class D>
HWY_INLINE void TestLeaf(D d, const KdTree& tree, const PacketRays& p, const Frames<D>& f,
                         const Group& g, size_t base, uint32_t first, uint32_t* lanes,
                         uint32_t* found, hn::Vec<D>* bt, Hit* best, PacketCounters* c) {
  const hn::RebindToUnsigned<D> du;
  const bool origins = p.has_origins;
  const uint32_t behind = p.behind >> base;
  const float* packet = tree.leaf_soa.data() + static_cast<size_t>(first) * kPacketFloats;
  for (;;) {
    uint32_t id[kPacketLanes];
    std::memcpy(id, packet + kPacketIds, sizeof(id));
    const bool last = (id[0] & kLastPacket) != 0;
    id[0] &= ~kLastPacket;
    for (int l = 0; l < kPacketLanes && *lanes != 0; ++l) {
      if (id[l] == kPadLane) break;  // pads only follow a leaf's last triangle
      const LaneShear<D> s = ShearLanes(d, f, BroadcastTriangle(d, g, packet, l));
      uint32_t rays = *lanes & ~RejectRays(d, f, s, behind & *lanes);
      // Unconditional: a branch on rays != 0 first mispredicts often on
      // shadow rays, most of whose tests reject every ray (paired rounds on
      // 8 scenes: shadow pass 1-10 % faster without it and TestLeafFew's).
      const uint32_t own =
          origins ? Bits(du, hn::Eq(hn::Load(du, p.origin + base), hn::Set(du, id[l]))) : 0;
      rays &= ~own;
      if (c != nullptr) CountStep(*lanes & ~own, &c->triangle_steps, &c->lanes.triangle_tests);
      if (rays == 0) continue;
      LaneHits lh;
      hn::Vec<D> t_vec = *bt;
      FinishLanes(d, f, s, rays, *bt, &lh, kAnyHit ? nullptr : &t_vec);
      uint32_t recorded = 0;
      for (uint32_t m = lh.hit; m != 0; m &= m - 1) {
        const int i = __builtin_ctz(m);
        if (Record<kAnyHit>(i, id[l], lh.t[i], lh.u[i], lh.v[i], &best[base + i], lanes, found)) {
          recorded |= 1u << i;
        }
      }
      if (!kAnyHit && recorded != 0) *bt = hn::IfThenElse(FromBits(d, recorded), t_vec, *bt);
      for (uint32_t m = lh.scalar; m != 0; m &= m - 1) {
        const int i = __builtin_ctz(m);
        if (ScalarTest<kAnyHit>(p, g, packet, l, id[l], base, i, lanes, found, best) && !kAnyHit) {
          SetLane(d, i, best[base + i].t, bt);
        }
      }
    }
    if (last || *lanes == 0) return;
    packet += kPacketFloats;
  }
}

// TestLeaf for at most Lanes(d) / kPacketLanes rays: each block of
// kPacketLanes vector lanes holds one ray (its frame permuted there) against
// the leaf packet's kPacketLanes triangles, so a leaf packet takes one vector
// test instead of one per triangle. The triangles of a leaf packet are
// tested at once, not one after the other; a hit beyond the ray's best so
// far is dropped by Record's Closer, so every ray ends with the same closest
// hit (any hit: a ray leaves at its first hit; the others found with it in
// the same vector are dropped).
template <bool kAnyHit, class D>
HWY_INLINE void TestLeafFew(D d, const KdTree& tree, const PacketRays& p, const Frames<D>& f,
                            const Group& g, size_t base, uint32_t first, uint32_t* lanes,
                            uint32_t* found, hn::Vec<D>* bt, Hit* best, PacketCounters* c) {
  const hn::RebindToUnsigned<D> du;
  const size_t n = hn::Lanes(d);
  // Block k holds ray ray[k]; blocks past the rays repeat the last one.
  int ray[kLanes / kPacketLanes];
  int rays_in = 0;
  for (uint32_t m = *lanes; m != 0; m &= m - 1) ray[rays_in++] = __builtin_ctz(m);
  // The kernel passes 1 to Lanes(d) / kPacketLanes rays (so ray[rays_in - 1]
  // below is a ray; telling the compiler also ends its -Warray-bounds).
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
    const auto ids = hn::And(
        hn::BitCast(du, hn::LoadDup128(d, packet + kPacketIds)),
        hn::LoadDup128(du, kIdMask));
    uint32_t live = 0;  // the blocks of rays still looking (any hit: some are done)
    for (int k = 0; k < rays_in; ++k) {
      if ((*lanes >> ray[k]) & 1) live |= kBlock << (k * kPacketLanes);
    }
    live &= ~Bits(du, hn::Eq(ids, hn::Set(du, kPadLane)));
    const LaneShear<D> s = ShearLanes(d, pf, RepeatTriangles(d, g, packet));
    uint32_t rays = live & ~RejectRays(d, pf, s, behind & live);
    const uint32_t own = p.has_origins ? Bits(du, hn::Eq(origin, ids)) : 0;
    rays &= ~own;  // no branch on rays (TestLeaf)
    if (c != nullptr) CountStep(live & ~own, &c->triangle_steps, &c->lanes.triangle_tests);
    if (rays != 0) {
      LaneHits lh;
      FinishLanes(d, pf, s, rays, hn::TableLookupLanes(*bt, perm), &lh);
      for (uint32_t m = lh.hit | lh.scalar; m != 0; m &= m - 1) {
        const int j = __builtin_ctz(m);
        const int i = index[j], l = j % kPacketLanes;
        if (kAnyHit && !((*lanes >> i) & 1)) continue;  // found already
        bool recorded;
        if ((lh.hit >> j) & 1) {
          recorded =
              Record<kAnyHit>(i, id[l], lh.t[j], lh.u[j], lh.v[j], &best[base + i], lanes, found);
        } else {
          recorded = ScalarTest<kAnyHit>(p, g, packet, l, id[l], base, i, lanes, found, best);
        }
        if (!kAnyHit && recorded) SetLane(d, i, best[base + i].t, bt);
      }
    }
    if (last || *lanes == 0) return;
    packet += kPacketFloats;
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace packet_internal
}  // namespace kdtree
HWY_AFTER_NAMESPACE();

#endif  // KDTREE_CC_KDTREE_LEAF_TEST_INL_H_
