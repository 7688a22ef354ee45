// Single rays through the BVH over the kd-tree's leaves (leaf_bvh.h): a
// node's eight boxes in vectors of the build's static Highway target (one
// vector where it has 256-bit vectors, two of SSE), the leaves with the
// kd-tree's leaf step (leaf_step-inl.h).
#include <cmath>
#include <optional>

#include "cc/kdtree/leaf_bvh.h"
#include "cc/kdtree/leaf_step-inl.h"
#include "cc/kdtree/slab_slots-inl.h"
#include "cc/kdtree/ray_setup.h"
#include "hwy/highway.h"

namespace kdtree {
namespace {

namespace hn = hwy::HWY_NAMESPACE;
namespace lane = packet_internal::HWY_NAMESPACE;
using DB = hn::CappedTag<float, kBvhWidth>;

struct Entry {
  uint32_t child;
  float t_near;  // where the ray enters the child's box (closest hit: pruning)
};

// What the box test needs of the ray (slab_slots-inl.h RaySlots), from its
// set-up: the reciprocals are the set-up's, not divided again (in-process
// A/B against three divisions here, 21 paired rounds, six scenes,
// 2026-12-07: T_R 0.987-1.000, within the noise).
struct BoxRay {
  explicit BoxRay(const RaySetup& s) {
    for (int k = 0; k < 3; ++k) {
      o[k] = hn::Set(DB(), s.org[k]);
      inv[k] = hn::Set(DB(), s.inv[k]);
      near_row[k] = s.negative[k] ? 3 + k : k;
      far_row[k] = s.negative[k] ? k : 3 + k;
    }
  }
  hn::Vec<DB> o[3], inv[3];
  int near_row[3], far_row[3];  // LeafBvhNode::box rows
};

constexpr IntersectionMode kMode = IntersectionMode::kWatertight;

// The leaf step's ray (leaf_step-inl.h LeafRay): set up with the ray when
// kLazy is false; else at the first leaf the ray reaches, with the
// watertight frame, which a ray that reaches no leaf never needs. Lazy for
// any hit: many shadow rays of the flat scenes reach no leaf (on city2 a
// shadow ray takes 5.0 node steps and 0.59 leaf steps; callgrind).
template <bool kLazy>
class LeafRayOf;

template <>
class LeafRayOf<false> {
 public:
  LeafRayOf(const Ray& ray, const RaySetup& setup, uint32_t origin_tri)
      : leaf_ray_(ray, setup.wray, origin_tri) {}
  const leaf_step::LeafRay<kMode>& Get() { return leaf_ray_; }

 private:
  const leaf_step::LeafRay<kMode> leaf_ray_;
};

template <>
class LeafRayOf<true> {
 public:
  // `ray`: the sanitised ray, which must outlive this.
  LeafRayOf(const Ray& ray, const RaySetup&, uint32_t origin_tri)
      : ray_(ray), origin_tri_(origin_tri) {}
  // A copy's LeafRay would refer to this one's frame.
  LeafRayOf(const LeafRayOf&) = delete;
  LeafRayOf& operator=(const LeafRayOf&) = delete;
  const leaf_step::LeafRay<kMode>& Get() {
    if (!leaf_ray_) {
      wray_ = MakeWatertightRay(ray_);  // SetUpVector's frame, bit for bit (ray_setup_test)
      leaf_ray_.emplace(ray_, wray_, origin_tri_);
    }
    return *leaf_ray_;
  }

 private:
  const Ray& ray_;
  const uint32_t origin_tri_;
  WatertightRay wray_;
  std::optional<leaf_step::LeafRay<kMode>> leaf_ray_;
};

// One function for the same reason as traversal.cc's Traverse: the set-up,
// the stack and the best hit stay in registers. kScaled: the box test's
// widening by one multiplication a side (slab_slots-inl.h RaySlots), for a
// ray with tmin >= 0.
//
// Any hit (shadow rays) sets up only what the box test needs
// (SetUpCommonBoxRay) and the leaf step's ray at its first leaf
// (LeafRayOf<true>); the answers are the same, as the root box's interval
// only ever ended a ray that the BVH's boxes also end: they lie in the
// scene's box, and the root test widens each slab more (kPad and the
// kd-tree's spatial tolerance) than a node's test (4 u). Against the set-up
// in full (in-process A/B, the two in one render_bench process, 21 paired
// rounds, kd_bvh; 2026-12-08): the shadow pass, its tracing alone, took 0.880 of the time on stk-candela-
// city, 0.911 on courtyard-1m and lost-empire, 0.923 on morse-kitchen,
// 0.935 on city2, 0.947 on rungholt-1m, 0.96-0.98 on bunny, teapots and
// fforest and 0.992 on hairball-1m, where the camera pass, the same code on
// both sides, gave 0.998-1.001; instructions per shadow ray (callgrind, an
// AVX2 build, the same rays): city2 798 -> 715, stk-candela-city 596 ->
// 463, bunny 1688 -> 1609, hairball-1m 2915 -> 2804 (Embree's
// rtcOccluded1 on city2: 458).
template <bool kAnyHit, bool kScaled>
Hit TraceLeafBvh(const LeafBvh& bvh, const Ray& input, uint32_t origin_tri) {
  const KdTree& leaves = bvh.leaves;
  Hit best;
  Ray ray = LoadRay(input);
  if (bvh.nodes.empty()) return best;
  RaySetup setup;  // the kd-tree's: the same sanitising, slack and watertight ray
  if (!(kAnyHit && SetUpCommonBoxRay(ray, &setup)) &&
      !SanitizeAndSetUpRay(&ray, leaves.bounds, &setup)) {
    return best;
  }
  best.t = ray.tmax;
  const float slack = kAnyHit ? 0.0f : setup.slack;  // any hit: unused (not set up)
  LeafRayOf<kAnyHit> leaf_ray(ray, setup, origin_tri);
  const BoxRay box_ray(setup);
  const float* soa = leaves.leaf_soa.data();
  const float* soa_end = soa + leaves.leaf_soa.size();
  const LeafBvhNode* nodes = bvh.nodes.data();
  Entry stack[kBvhWidth * kMaxTraversalStack];
  int top = 0;
  uint32_t child = 0;  // the root node
  for (;;) {
    while (!(child & LeafBvhNode::kLeafBit)) {
      const LeafBvhNode& node = nodes[child];
      HWY_ALIGN float t_near[kBvhWidth];
      uint32_t mask =
          lane::RaySlots<DB, kScaled>(DB(), node, box_ray.o, box_ray.inv, box_ray.near_row,
                                      box_ray.far_row, ray.tmin,
                                      kAnyHit ? best.t : best.t + slack, t_near);
      if (mask == 0) goto next;
      const int first = __builtin_ctz(mask);
      mask &= mask - 1;
      if (mask == 0) {  // one child: no stack
        child = node.child[first];
        continue;
      }
      // Several: onto the stack sorted, the one to visit first on top
      // (closest hit: the nearest entry; any hit: the farthest).
      const int base = top;
      stack[top++] = Entry{node.child[first], t_near[first]};
      for (; mask != 0; mask &= mask - 1) {
        const int s = __builtin_ctz(mask);
        const Entry e{node.child[s], t_near[s]};
        int j = top++;
        while (j > base && (kAnyHit ? stack[j - 1].t_near > e.t_near
                                    : stack[j - 1].t_near < e.t_near)) {
          stack[j] = stack[j - 1];
          --j;
        }
        stack[j] = e;
      }
      child = stack[--top].child;
    }
    {
      const float* packet =
          soa + static_cast<size_t>(child & ~LeafBvhNode::kLeafBit) * kPacketFloats;
      if (leaf_step::TestLeaf<kAnyHit, false, kMode>(leaf_ray.Get(), packet, soa_end, &best,
                                                     nullptr)) {
        return best;
      }
    }
  next:
    // A child whose box starts beyond the best hit (with the slack for the
    // rounding of triangle distances) cannot hold a nearer one or a tie.
    for (;;) {
      if (top == 0) {
        if (!best.hit()) best.t = INFINITY;
        return best;
      }
      const Entry& e = stack[--top];
      if (!kAnyHit && e.t_near > best.t + slack) continue;
      child = e.child;
      break;
    }
  }
}

}  // namespace

Hit IntersectLeafBvh(const LeafBvh& bvh, const Ray& ray) {
  if (ray.tmin >= 0.0f) return TraceLeafBvh<false, true>(bvh, ray, kNoHit);
  return TraceLeafBvh<false, false>(bvh, ray, kNoHit);
}

bool OccludedLeafBvh(const LeafBvh& bvh, const Ray& ray, uint32_t origin_tri) {
  if (ray.tmin >= 0.0f) return TraceLeafBvh<true, true>(bvh, ray, origin_tri).hit();
  return TraceLeafBvh<true, false>(bvh, ray, origin_tri).hit();
}

}  // namespace kdtree
