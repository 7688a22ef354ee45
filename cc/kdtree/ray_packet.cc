#include "cc/kdtree/ray_packet.h"

#include <algorithm>
#include <cassert>
#include <cstdint>

#include "cc/geometry/ray_check.h"
#include "cc/geometry/watertight.h"
#include "cc/kdtree/leaf_layout.h"
#include "cc/kdtree/packet_rays.h"
#include "cc/kdtree/ray_setup.h"

namespace kdtree {
namespace {

using packet_internal::Group;
using packet_internal::PacketRays;
using packet_internal::SetUpLanes;
static_assert(packet_internal::kLanes == kRayPacketSize, "one packet, one PacketRays");

bool TreeSupportsPackets(const KdTree& tree, const TraversalOptions& options) {
  return options.mode == IntersectionMode::kWatertight && !tree.nodes.empty() &&
         tree.bounds.Valid();
}

// The ray's components in lane i.
void PutRay(const Ray& ray, int i, PacketRays* p) {
  for (int k = 0; k < 3; ++k) {
    p->org[k][i] = ray.origin[k];
    p->dir[k][i] = ray.dir[k];
  }
  p->tmin[i] = ray.tmin;
  p->tmax[i] = ray.tmax;
}

// Lane i's set-up from SetUpRay's scalar path (a zero direction component).
void SetLane(const RaySetup& s, int i, PacketRays* p) {
  for (int k = 0; k < 3; ++k) {
    p->inv[k][i] = s.inv[k];
    p->tol[k][i] = s.tol[k];
  }
  p->t_entry[i] = s.t_entry;
  p->t_exit[i] = s.t_exit;
  p->slack[i] = s.slack;
  p->delta[i] = s.delta;
  const WatertightRay& w = s.wray;
  p->ox[i] = w.ox;
  p->oy[i] = w.oy;
  p->oz[i] = w.oz;
  p->sx[i] = w.sx;
  p->sy[i] = w.sy;
  p->sz[i] = w.sz;
  p->shear_weight[i] = watertight_internal::ShearWeight(w);
  // kx and ky follow from kz and the sign of dir[kz] (WatertightAxes).
  packet_internal::SetLaneKey(p, i, s.negative, w.kz);
}

// The packet's rays, set up and traced group by group; returns the lanes
// with a hit. For the closest hit, hits[i] gets ray i's (the others are not
// touched); an any-hit search writes nothing (hits may be null). origins may
// be null (none). As the BVH's packets (leaf_bvh_packet_kernel.cc
// TraceBvhPacket): no packet of Hits to fill, copy and read back.
uint32_t TracePacket(const KdTree& tree, const Ray* rays, int n, const uint32_t* origins,
                     packet_internal::Search search, Hit* hits, PacketCounters* counters) {
  return packet_internal::TracePacketGroups(
      tree, rays, n, origins, counters, [&](const PacketRays& p, const Group& g) {
        return packet_internal::TraceGroup(tree, p, g, search, hits, counters);
      });
}

TraversalCounters* LaneCounters(PacketCounters* counters) {
  return counters != nullptr ? &counters->lanes : nullptr;
}

// The origin triangles TracePacket takes: `given` (one per ray) if not null,
// else options' one triangle for all n rays (in *store), else null (none).
const uint32_t* PacketOrigins(const uint32_t* given, const TraversalOptions& options, int n,
                              uint32_t (&store)[kRayPacketSize]) {
  if (given != nullptr) return given;
  if (options.origin_tri == kNoHit) return nullptr;
  std::fill_n(store, n, options.origin_tri);
  return store;
}

}  // namespace

bool PacketPathApplies(const KdTree& tree, const TraversalOptions& options) {
  return TreeSupportsPackets(tree, options);
}

const char* PacketKernelTarget() { return packet_internal::KernelTarget(); }

void IntersectPacket(const KdTree& tree, const Ray* rays, int n, Hit* hits,
                     const TraversalOptions& options, PacketCounters* counters) {
  if (!TreeSupportsPackets(tree, options)) {
    for (int i = 0; i < n; ++i) hits[i] = Intersect(tree, rays[i], options, LaneCounters(counters));
    return;
  }
  uint32_t store[kRayPacketSize] = {};
  for (int i = 0; i < n; ++i) hits[i] = Hit();
  TracePacket(tree, rays, n, PacketOrigins(nullptr, options, n, store),
              packet_internal::Search::kClosest, hits, counters);
}

void OccludedPacket(const KdTree& tree, const Ray* rays, int n, const uint32_t* origin_tris,
                    bool* occluded, const TraversalOptions& options, PacketCounters* counters) {
  assert(origin_tris == nullptr || options.origin_tri == kNoHit);
  if (!TreeSupportsPackets(tree, options)) {
    TraversalOptions one = options;
    for (int i = 0; i < n; ++i) {
      if (origin_tris != nullptr) one.origin_tri = origin_tris[i];
      occluded[i] = Occluded(tree, rays[i], one, LaneCounters(counters));
    }
    return;
  }
  // The packet path is the watertight test's (TreeSupportsPackets), where the
  // origin triangle may be skipped.
  uint32_t store[kRayPacketSize] = {};
  using packet_internal::Search;
  const uint32_t found =
      TracePacket(tree, rays, n, PacketOrigins(origin_tris, options, n, store),
                  options.from_end ? Search::kAnyFromEnd : Search::kAny, nullptr, counters);
  for (int i = 0; i < n; ++i) occluded[i] = (found >> i) & 1;
}


namespace packet_internal {

// The set-up of each ray as the single-ray traversal does it (SanitizeRay,
// then SetUpRay: its vector path for every lane at once, its scalar path for
// a ray with a zero direction component); rays that miss the tree's box are
// not live.
void PreparePacket(const KdTree& tree, const Ray* rays, int n, const uint32_t* origins,
                   PacketRays* p) {
  assert(n >= 0 && n <= kRayPacketSize);
  if (n == 0) return;
  uint32_t zero = 0;
  const uint32_t valid = packet_internal::LoadLanes(rays, n, p, &zero);
  if (valid == 0) return;
  const uint32_t plain = valid & ~zero;
  // The lanes with a zero direction component are set up below, from
  // lanes whose frames must then be finite (LoadLanes copied a plain
  // lane's ray into them): frames for all lanes if there are any.
  p->live = SetUpLanes(tree.bounds, p, /*frames_if_none=*/zero != 0) & plain;
  // A ray with a zero direction component: SanitizeRay's ray (its zero
  // signed), set up alone.
  for (uint32_t m = zero; m != 0; m &= m - 1) {
    const int i = __builtin_ctz(m);
    Ray ray = rays[i];
    SanitizeRay(&ray);
    RaySetup s;
    if (!SetUpRayScalar(ray, tree.bounds, &s)) continue;
    PutRay(ray, i, p);
    SetLane(s, i, p);
    p->live |= 1u << i;
  }
  // Origin triangles of the live lanes (which are among the n rays).
  if (origins == nullptr) {
    for (int i = 0; i < kRayPacketSize; ++i) p->origin[i] = kNoHit;
    p->has_origins = false;
    return;
  }
  uint32_t any = 0;
  for (int i = 0; i < kRayPacketSize; ++i) {
    p->origin[i] = (p->live >> i) & 1 ? origins[i] : kNoHit;
    any |= p->origin[i] ^ kNoHit;
  }
  p->has_origins = any != 0;
}

// The next group of *rest's lanes: those with the same direction signs and
// watertight axes as its lowest (packet_rays.h).
Group NextGroup(const PacketRays& p, uint32_t* rest) {
  const int first = __builtin_ctz(*rest);
  Group g;
  g.lanes = SameKey(p, first, *rest);
  *rest &= ~g.lanes;
  for (int k = 0; k < 3; ++k) g.negative[k] = LaneNegative(p, first, k);
  WatertightAxes(Vec3(p.dir[0][first], p.dir[1][first], p.dir[2][first]), &g.kx, &g.ky, &g.kz);
  return g;
}

}  // namespace packet_internal

}  // namespace kdtree
