// Single rays through the BVH over the kd-tree's leaves (leaf_bvh.h): a
// node's eight boxes in vectors of the build's static Highway target (one
// vector where it has 256-bit vectors, two of SSE), the leaves with the
// kd-tree's leaf step (leaf_step-inl.h).
#include <cmath>

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

// One function for the same reason as traversal.cc's Traverse: the set-up,
// the stack and the best hit stay in registers.
template <bool kAnyHit>
Hit TraceLeafBvh(const LeafBvh& bvh, const Ray& input, uint32_t origin_tri) {
  const KdTree& leaves = bvh.leaves;
  constexpr IntersectionMode kMode = IntersectionMode::kWatertight;
  Hit best;
  Ray ray = LoadRay(input);
  if (bvh.nodes.empty()) return best;
  RaySetup setup;  // the kd-tree's: the same sanitising, slack and watertight ray
  if (!SanitizeAndSetUpRay(&ray, leaves.bounds, &setup)) return best;
  best.t = ray.tmax;
  const float slack = setup.slack;
  const leaf_step::LeafRay<kMode> leaf_ray(ray, setup.wray, origin_tri);
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
          lane::RaySlots(DB(), node, box_ray.o, box_ray.inv, box_ray.near_row, box_ray.far_row,
                         ray.tmin, kAnyHit ? best.t : best.t + slack, t_near);
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
      if (leaf_step::TestLeaf<kAnyHit, false, kMode>(leaf_ray, packet, soa_end, &best, nullptr)) {
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
  return TraceLeafBvh<false>(bvh, ray, kNoHit);
}

bool OccludedLeafBvh(const LeafBvh& bvh, const Ray& ray, uint32_t origin_tri) {
  return TraceLeafBvh<true>(bvh, ray, origin_tri).hit();
}

}  // namespace kdtree
