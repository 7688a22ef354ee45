// A packet's rays after their set-up, as a structure of arrays the wide
// kernel (ray_packet_kernel.cc) loads a vector of lanes at a time. Filled by
// ray_packet.cc; internal to the packet traversal.
#ifndef KDTREE_CC_KDTREE_PACKET_RAYS_H_
#define KDTREE_CC_KDTREE_PACKET_RAYS_H_

#include <cstdint>
#include <vector>

#include "cc/geometry/ray.h"
#include "cc/geometry/watertight.h"
#include "cc/kdtree/ray_packet.h"
#include "cc/kdtree/tree.h"

namespace kdtree {

namespace packet_internal {

inline constexpr int kLanes = 16;  // rays per packet (kRayPacketSize)

// Per lane i, the values of RaySetup (ray_setup.h) and of the ray's
// WatertightRay. Lanes without a valid ray hold a copy of a valid one (so
// that their arithmetic stays finite); only live lanes are ever traced.
struct PacketRays {
  // The rays after SanitizeRay, by component.
  alignas(64) float dir[3][kLanes];
  alignas(64) float tmin[kLanes];
  alignas(64) float tmax[kLanes];
  alignas(64) float org[3][kLanes];
  alignas(64) float inv[3][kLanes];
  alignas(64) float tol[3][kLanes];
  alignas(64) float t_entry[kLanes];
  alignas(64) float t_exit[kLanes];
  alignas(64) float slack[kLanes];
  alignas(64) float delta[kLanes];
  // The watertight frame's origin (ox, oy, oz), shear (sx, sy, sz) and the
  // shear weight of its edge bound (watertight.h ShearWeight).
  alignas(64) float ox[kLanes], oy[kLanes], oz[kLanes];
  alignas(64) float sx[kLanes], sy[kLanes], sz[kLanes];
  alignas(64) float shear_weight[kLanes];
  // The triangle each ray leaves from, never tested (kNoHit: none).
  alignas(64) uint32_t origin[kLanes];
  // The lanes' keys, which lanes with the same one traverse together
  // (Group), a bit per lane: in key_bits[k] for k < 3, the sign of the
  // direction on axis k (1: negative); in key_bits[3] and key_bits[4],
  // whether the watertight kz is 1 or 2.
  uint32_t key_bits[5] = {0, 0, 0, 0, 0};
  uint32_t live = 0;    // bit i: ray i reaches the tree
  uint32_t behind = 0;  // bit i: ray i has tmin >= 0 (lane_test-inl.h RejectRays)
  bool has_origins = false;  // some lane has an origin triangle
};

// Lane i's WatertightRay (MakeWatertightRay's values), its axes g's.
inline WatertightRay LaneRay(const PacketRays& p, int kx, int ky, int kz, int i) {
  WatertightRay w;
  w.kx = kx;
  w.ky = ky;
  w.kz = kz;
  w.ox = p.ox[i];
  w.oy = p.oy[i];
  w.oz = p.oz[i];
  w.sx = p.sx[i];
  w.sy = p.sy[i];
  w.sz = p.sz[i];
  w.origin = Vec3(p.org[0][i], p.org[1][i], p.org[2][i]);
  w.dir = Vec3(p.dir[0][i], p.dir[1][i], p.dir[2][i]);
  return w;
}

// Lane i's direction sign on axis k (true: negative) and watertight kz.
inline bool LaneNegative(const PacketRays& p, int i, int k) { return (p.key_bits[k] >> i) & 1; }
inline int LaneKz(const PacketRays& p, int i) {
  return (p.key_bits[3] >> i) & 1 ? 1 : (p.key_bits[4] >> i) & 1 ? 2 : 0;
}

// Lane i's key from its direction signs and kz.
inline void SetLaneKey(PacketRays* p, int i, const bool negative[3], int kz) {
  const bool bit[5] = {negative[0], negative[1], negative[2], kz == 1, kz == 2};
  for (int b = 0; b < 5; ++b) {
    p->key_bits[b] = (p->key_bits[b] & ~(1u << i)) | static_cast<uint32_t>(bit[b]) << i;
  }
}

// The lanes of `lanes` with lane i's key.
inline uint32_t SameKey(const PacketRays& p, int i, uint32_t lanes) {
  for (const uint32_t bits : p.key_bits) lanes &= (bits >> i) & 1 ? bits : ~bits;
  return lanes;
}

// The lanes that traverse together: the same direction sign on every axis
// (so the same near child at every node) and the same watertight axes (so
// the same vertex components are loaded for every lane).
struct Group {
  uint32_t lanes = 0;
  bool negative[3] = {false, false, false};
  int kx = 0, ky = 1, kz = 2;
};

inline constexpr uint32_t kAllLanes = (1u << kLanes) - 1;

// SanitizeRay (ray_check.h) for rays[0, n), 1 <= n <= kLanes, in vectors:
// their components, sanitized, into the lanes of p (org, dir, tmin, tmax;
// lanes without a valid ray, lanes n and up included, or with a zero
// direction component get those of the first valid ray without one, else of
// the first valid ray) and p->behind; returns the lanes with a valid ray, and
// in *zero those with a zero direction component. On targets of 16 lanes
// the rays are read by wide loads and permutes (geometry/ray_rows-inl.h),
// elsewhere by gathers. Chosen at run time like TraceGroup.
uint32_t LoadLanes(const Ray* rays, int n, PacketRays* p, uint32_t* zero);

// SetUpRay (ray_setup.h) for every lane from its ray's components (dir, org,
// tmin, tmax; no direction component zero), with the same float operations:
// fills the lanes' set-up and keys; returns the lanes whose ray reaches the
// box. When none does and frames_if_none is false, only what the box test
// needs is filled (inv, delta, tol, t_entry, t_exit; the keys are 0): a
// packet none of whose lanes is live reads nothing else. In-process A/B
// (7 paired rounds, eight scenes; 2026-12-07): camera pass 0.988-0.998 of
// the time (most camera packets pass the scene by), where the control (the
// same code on both sides) gave 1.001-1.012. Vector code, chosen at run
// time like TraceGroup.
uint32_t SetUpLanes(const AABB& box, PacketRays* p, bool frames_if_none = true);

// Loads rays[0, n) (n <= kLanes) into *p and sets up the lanes that reach
// the tree's box (p->live), each with origins[i] as its origin triangle
// (origins may be null: none; ray_packet.cc).
void PreparePacket(const KdTree& tree, const Ray* rays, int n, const uint32_t* origins,
                   PacketRays* p);

// The next group of the lanes in *rest (lanes with the same key as its
// lowest), taken out of *rest; *rest must not be 0.
Group NextGroup(const PacketRays& p, uint32_t* rest);

// The packet's rays set up (PreparePacket) and traced group by group
// (NextGroup), each group by trace(p, g), which returns its lanes with a
// hit; returns the union. Counts the rays, the packets that reach the tree
// and the groups in `counters` (may be null). The kd-tree's packets
// (ray_packet.cc) and the BVH's (leaf_bvh_packet_kernel.cc) differ only in
// `trace`. Always inlined, so that each caller compiles as if the loop were
// written there (a first version, a plain template, was compiled as a
// function of its own, and the best mode's renders seemed slower by a few
// per cent; with the inlining the callers' machine code is the one they
// had when each held its own copy of the loop).
template <class TraceFn>
inline __attribute__((always_inline)) uint32_t TracePacketGroups(
    const KdTree& tree, const Ray* rays, int n, const uint32_t* origins, PacketCounters* counters,
    TraceFn trace) {
  PacketRays p;
  PreparePacket(tree, rays, n, origins, &p);
  if (counters != nullptr) {
    counters->lanes.rays += static_cast<uint64_t>(n);
    counters->packets += p.live != 0;
  }
  uint32_t found = 0;
  for (uint32_t rest = p.live; rest != 0;) {
    const Group g = NextGroup(p, &rest);
    if (counters != nullptr) ++counters->groups;
    found |= trace(p, g);
  }
  return found;
}

// What a trace looks for: the closest hit (Intersect), or any hit (Occluded)
// with a node's children taken front to back or from the rays' ends
// (TraversalOptions::from_end).
enum class Search { kClosest, kAny, kAnyFromEnd };

// Traces the group's lanes through tree; returns those with a hit. For the
// closest hit, best[i] gets the hit of each such lane i (the other entries
// are not touched); an any-hit search writes nothing (best may be null). Chosen at
// run time for the CPU (Highway's dynamic dispatch: ray_packet_kernel.cc).
// `counters` (may be null): what the traversal did (ray_packet.h).
uint32_t TraceGroup(const KdTree& tree, const PacketRays& p, const Group& g, Search search,
                    Hit* best, PacketCounters* counters);

// The Highway target TraceGroup runs on now ("AVX3", "AVX2", "SSE4", ...).
const char* KernelTarget();

// The Highway targets this machine can run the kernel on (for tests:
// hwy::SetSupportedTargetsForTest(target) makes TraceGroup use one).
std::vector<int64_t> KernelTargets();

}  // namespace packet_internal
}  // namespace kdtree

#endif  // KDTREE_CC_KDTREE_PACKET_RAYS_H_
