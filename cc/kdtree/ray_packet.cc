#include "cc/kdtree/ray_packet.h"

#include <cassert>
#include <cmath>
#include <cstdint>

#include "cc/geometry/ray_check.h"
#include "cc/geometry/watertight.h"
#include "cc/kdtree/leaf_layout.h"
#include "cc/kdtree/packet_reject.h"
#include "cc/kdtree/ray_setup.h"
#include "cc/kdtree/ray_setup4.h"

#include <immintrin.h>

namespace kdtree {
namespace {

constexpr int kAll = (1 << kRayPacketSize) - 1;

// The lanes' rays after SanitizeRay and their set-up; `live` has bit i set for
// the rays that reach the tree (the others miss, as in the single-ray
// traversal).
struct Packet {
  Ray ray[kRayPacketSize];
  RaySetup4 setup;
  int live = 0;
  // Per lane, the triangle the ray leaves (TraversalOptions::origin_tri),
  // never tested; kNoHit for none.
  uint32_t origin[kRayPacketSize] = {kNoHit, kNoHit, kNoHit, kNoHit};
  bool negative[3] = {false, false, false};
  bool same_signs = true;  // every live ray has `negative`'s signs
};

bool TreeSupportsPackets(const KdTree& tree, const TraversalOptions& options) {
  return options.mode == IntersectionMode::kWatertight && !options.mailbox &&
         HasLeafLayout(tree) && !tree.nodes.empty() && tree.bounds.Valid();
}

void Prepare(const KdTree& tree, const Ray* rays, int n, Packet* p) {
  assert(n >= 0 && n <= kRayPacketSize);
  int valid = 0;
  bool zero = false;  // some direction component is zero
  for (int i = 0; i < n; ++i) {
    p->ray[i] = rays[i];
    if (!SanitizeRay(&p->ray[i])) continue;
    valid |= 1 << i;
    const Vec3& d = p->ray[i].dir;
    zero = zero || d.x == 0.0f || d.y == 0.0f || d.z == 0.0f;
  }
  if (valid == 0) return;
  if (zero) {
    // SetUpRay's scalar path, ray by ray.
    for (int i = 0; i < n; ++i) {
      RaySetup one;
      if ((valid & (1 << i)) && SetUpRay(p->ray[i], tree.bounds, &one)) {
        SetLane(one, i, &p->setup);
        p->live |= 1 << i;
      }
    }
  } else {
    // Lanes without a valid ray compute a copy of a valid one, then drop out.
    const int first = __builtin_ctz(valid);
    for (int i = 0; i < kRayPacketSize; ++i) {
      if (!(valid & (1 << i))) p->ray[i] = p->ray[first];
    }
    p->live = SetUpRays4(p->ray, tree.bounds, &p->setup) & valid;
  }
  if (p->live == 0) return;
  const int first = __builtin_ctz(p->live);
  for (int k = 0; k < 3; ++k) p->negative[k] = p->setup.negative[first][k];
  for (int i = 0; i < kRayPacketSize; ++i) {
    if (!(p->live & (1 << i))) continue;
    for (int k = 0; k < 3; ++k) {
      p->same_signs = p->same_signs && p->setup.negative[i][k] == p->negative[k];
    }
  }
}

// Lane masks as vectors: kLaneMask[m] has lane i all ones when bit i of m is set.
alignas(16) constexpr uint32_t kLaneMask[16][4] = {
    {0, 0, 0, 0},  {~0u, 0, 0, 0},  {0, ~0u, 0, 0},  {~0u, ~0u, 0, 0},
    {0, 0, ~0u, 0},  {~0u, 0, ~0u, 0},  {0, ~0u, ~0u, 0},  {~0u, ~0u, ~0u, 0},
    {0, 0, 0, ~0u},  {~0u, 0, 0, ~0u},  {0, ~0u, 0, ~0u},  {~0u, ~0u, 0, ~0u},
    {0, 0, ~0u, ~0u},  {~0u, 0, ~0u, ~0u},  {0, ~0u, ~0u, ~0u},  {~0u, ~0u, ~0u, ~0u}};

inline __m128 LaneMask(int m) {
  return _mm_load_ps(reinterpret_cast<const float*>(kLaneMask[m]));
}
// a where the mask is clear, b where it is set.
inline __m128 Select(__m128 a, __m128 b, __m128 mask) {
  return _mm_or_ps(_mm_andnot_ps(mask, a), _mm_and_ps(mask, b));
}

struct PacketEntry {
  __m128 t_entry, t_exit;
  uint32_t node;
  int lanes;
};

template <bool kAnyHit>
void Trace(const KdTree& tree, const Packet& p, Hit* best) {
  const RaySetup4& s = p.setup;
  __m128 org[3], inv[3], tol[3];
  for (int k = 0; k < 3; ++k) {
    org[k] = _mm_load_ps(s.org[k]);
    inv[k] = _mm_load_ps(s.inv[k]);
    tol[k] = _mm_load_ps(s.tol[k]);
  }
  alignas(16) float best_t[4] = {};
  for (int i = 0; i < kRayPacketSize; ++i) {
    if (!(p.live & (1 << i))) continue;
    best_t[i] = p.ray[i].tmax;
    best[i].t = p.ray[i].tmax;
  }
  const __m128 slack = _mm_load_ps(s.slack);
  const __m128 abs_mask = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff));
  const __m128 inf = _mm_set1_ps(INFINITY);
  __m128 t_entry = _mm_load_ps(s.t_entry), t_exit = _mm_load_ps(s.t_exit);

  const KdNode* nodes = tree.leaf_nodes.data();
  const float* soa = tree.leaf_soa.data();
  PacketEntry stack[kMaxTraversalStack];
  int top = 0;
  int lanes = p.live;  // lanes that visit the current node
  int found = 0;       // lanes with a hit (any hit: done)
  uint32_t index = 0;
  for (;;) {
    const KdNode* node = &nodes[index];
    while (!node->is_leaf()) {
      const int axis = node->axis();
      const __m128 t_split = _mm_mul_ps(_mm_sub_ps(_mm_set1_ps(node->split), org[axis]), inv[axis]);
      const __m128 t_tol = tol[axis];
      const uint32_t left = index + 1, right = node->index();
      const uint32_t near = p.negative[axis] ? right : left;
      const uint32_t far = p.negative[axis] ? left : right;
      // The single-ray rules (traversal.cc), per lane.
      const __m128 near_only_v = _mm_cmpgt_ps(t_split, _mm_add_ps(t_exit, t_tol));
      const __m128 far_only_v =
          _mm_andnot_ps(near_only_v, _mm_cmplt_ps(t_split, _mm_sub_ps(t_entry, t_tol)));
      const int near_only = _mm_movemask_ps(near_only_v) & lanes;
      const int far_only = _mm_movemask_ps(far_only_v) & lanes;
      if (far_only == lanes) {
        index = far;
      } else if (near_only == lanes) {
        index = near;
      } else {
        int both = lanes & ~near_only & ~far_only;
        int need_near = near_only | both, need_far = far_only | both;
        // Both children, on [t_entry, ts + tol] and [ts - tol, t_exit], ts
        // t_split clamped to the interval (MAXPS / MINPS pick what the
        // scalar comparisons pick).
        const __m128 ts = _mm_min_ps(t_exit, _mm_max_ps(t_entry, t_split));
        __m128 far_entry = _mm_sub_ps(ts, t_tol), near_exit = _mm_add_ps(ts, t_tol);
        const int finite = _mm_movemask_ps(_mm_cmplt_ps(_mm_and_ps(t_split, abs_mask), inf));
        if ((both & ~finite) != 0) {
          // Parallel to the plane or in it (t_split infinite or NaN): both
          // children whole when the origin is within delta of the plane, else
          // the side the origin is on.
          for (int i = 0; i < kRayPacketSize; ++i) {
            if (!((both & ~finite) & (1 << i))) continue;
            const float gap = node->split - s.org[axis][i];
            // Within delta: both children whole (in need_near and need_far,
            // dropped from `both` below, so no clamp).
            if (!(std::fabs(gap) <= s.delta[i])) {
              const bool to_near = (gap > 0) == (near == left);
              need_near &= to_near ? kAll : ~(1 << i);
              need_far &= to_near ? ~(1 << i) : kAll;
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
          const __m128 clamp = LaneMask(both);
          assert(top < kMaxTraversalStack);
          stack[top++] = PacketEntry{Select(t_entry, far_entry, clamp), t_exit, far, need_far};
          t_exit = Select(t_exit, near_exit, clamp);
          index = near;
          lanes = need_near;
        }
      }
      node = &nodes[index];
    }
    // Leaf: each lane's ray against the leaf's packets of 4 triangles.
    const uint32_t first = node->index();
    const float* packet =
        first == kEmptyLeaf ? nullptr : soa + static_cast<size_t>(first) * kPacketFloats;
    while (packet != nullptr) {
      const __m128i ids = _mm_loadu_si128(reinterpret_cast<const __m128i*>(packet + kPacketIds));
      const int tri_lanes =
          _mm_movemask_ps(_mm_castsi128_ps(_mm_cmpeq_epi32(ids, _mm_set1_epi32(-1)))) ^ 0xF;
      alignas(16) uint32_t id[kPacketLanes];
      _mm_store_si128(reinterpret_cast<__m128i*>(id), ids);
      const bool last = (id[0] & kLastPacket) != 0;
      id[0] &= ~kLastPacket;
      const __m128i clean_ids = _mm_load_si128(reinterpret_cast<const __m128i*>(id));
      for (int rays = lanes; rays != 0; rays &= rays - 1) {
        const int r = __builtin_ctz(rays);
        const WatertightRay& wray = s.wray[r];
        Hit& b = best[r];
        // The lane's origin triangle stays untested, as in the single-ray
        // traversal (traversal.cc).
        const int origin = _mm_movemask_ps(_mm_castsi128_ps(
            _mm_cmpeq_epi32(clean_ids, _mm_set1_epi32(static_cast<int>(p.origin[r])))));
        int live = tri_lanes & ~origin & ~RejectMask4(wray, packet, p.ray[r].tmin >= 0.0f);
        while (live != 0) {
          const int l = __builtin_ctz(live);
          live &= live - 1;
          const Vec3 a(packet[0 * 4 + l], packet[1 * 4 + l], packet[2 * 4 + l]);
          const Vec3 bv(packet[3 * 4 + l], packet[4 * 4 + l], packet[5 * 4 + l]);
          const Vec3 c(packet[6 * 4 + l], packet[7 * 4 + l], packet[8 * 4 + l]);
          float t, u, v;
          if (IntersectTriangleWatertight(wray, a, bv, c, p.ray[r].tmin, b.t, &t, &u, &v) &&
              (kAnyHit || Closer(t, id[l], b))) {
            b.tri = id[l];
            b.t = t;
            b.u = u;
            b.v = v;
            found |= 1 << r;
            if (kAnyHit) {
              lanes &= ~(1 << r);
              break;
            }
          }
        }
        if (!kAnyHit) best_t[r] = b.t;
      }
      if (kAnyHit && lanes == 0) break;
      packet = last ? nullptr : packet + kPacketFloats;
    }
    if (kAnyHit && found == p.live) return;
    // Next node: each lane drops it when it starts beyond that lane's best
    // hit plus slack (any hit: lanes with a hit are done).
    for (;;) {
      if (top == 0) {
        if (!kAnyHit) {
          for (int i = 0; i < kRayPacketSize; ++i) {
            if ((p.live & (1 << i)) && !best[i].hit()) best[i].t = INFINITY;
          }
        }
        return;
      }
      const PacketEntry& e = stack[--top];
      int m = e.lanes & ~(kAnyHit ? found : 0);
      if (!kAnyHit && (m & found) != 0) {
        const __m128 limit = _mm_add_ps(_mm_load_ps(best_t), slack);
        m &= ~(_mm_movemask_ps(_mm_cmpgt_ps(e.t_entry, limit)) & found);
      }
      if (m == 0) continue;
      lanes = m;
      index = e.node;
      t_entry = e.t_entry;
      t_exit = e.t_exit;
      break;
    }
  }
}

// Prepares the packet; false when the packet path does not apply (the rays
// are then traced one by one).
bool PreparePacket(const KdTree& tree, const Ray* rays, int n, const TraversalOptions& options,
                   Packet* p) {
  if (!TreeSupportsPackets(tree, options)) return false;
  Prepare(tree, rays, n, p);
  return p->same_signs;
}

}  // namespace

bool PacketPathApplies(const KdTree& tree, const Ray* rays, int n,
                       const TraversalOptions& options) {
  Packet p;
  return PreparePacket(tree, rays, n, options, &p);
}

void IntersectPacket(const KdTree& tree, const Ray* rays, int n, Hit* hits,
                     const TraversalOptions& options) {
  Packet p;
  if (!PreparePacket(tree, rays, n, options, &p)) {
    for (int i = 0; i < n; ++i) hits[i] = Intersect(tree, rays[i], options);
    return;
  }
  for (int i = 0; i < n; ++i) {
    hits[i] = Hit();
    p.origin[i] = options.origin_tri;
  }
  if (p.live != 0) Trace<false>(tree, p, hits);
}

void OccludedPacket(const KdTree& tree, const Ray* rays, int n, const uint32_t* origin_tris,
                    bool* occluded, const TraversalOptions& options) {
  assert(origin_tris == nullptr || options.origin_tri == kNoHit);
  Packet p;
  if (!PreparePacket(tree, rays, n, options, &p)) {
    TraversalOptions one = options;
    for (int i = 0; i < n; ++i) {
      if (origin_tris != nullptr) one.origin_tri = origin_tris[i];
      occluded[i] = Occluded(tree, rays[i], one);
    }
    return;
  }
  // The packet path is the watertight test's (TreeSupportsPackets), where the
  // origin triangle may be skipped.
  for (int i = 0; i < n; ++i) {
    p.origin[i] = origin_tris != nullptr ? origin_tris[i] : options.origin_tri;
  }
  Hit hits[kRayPacketSize];
  if (p.live != 0) Trace<true>(tree, p, hits);
  for (int i = 0; i < n; ++i) occluded[i] = hits[i].hit();
}

}  // namespace kdtree
