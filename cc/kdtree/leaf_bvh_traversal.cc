// Single rays through the BVH over the kd-tree's leaves (leaf_bvh.h): a
// node's eight boxes in vectors of the build's static Highway target (one
// vector where it has 256-bit vectors, two of SSE), the leaves with the
// kd-tree's leaf step (leaf_step-inl.h).
#include <cmath>

#include "cc/kdtree/leaf_bvh.h"
#include "cc/kdtree/leaf_step-inl.h"
#include "cc/kdtree/ray_setup.h"
#include "hwy/highway.h"

namespace kdtree {
namespace {

namespace hn = hwy::HWY_NAMESPACE;
namespace lane = packet_internal::HWY_NAMESPACE;
using DB = hn::CappedTag<float, kBvhWidth>;
constexpr int kBoxLanes = static_cast<int>(hn::MaxLanes(DB()));
static_assert(kBvhWidth % kBoxLanes == 0, "a node's slots in whole vectors");
static_assert(HWY_ARCH_X86, "BoxRay relies on x86's max and min with a NaN operand");

struct Entry {
  uint32_t child;
  float t_near;  // where the ray enters the child's box (closest hit: pruning)
};

// What the box test needs of the ray. A direction component of +-0 (or
// whose reciprocal overflows) gives an infinite reciprocal, and a slab
// distance (b - o) * inf is NaN when the origin lies on the slab's plane;
// the distances are combined so that a NaN is passed over (x86's max and
// min return their second operand when one is NaN, and a NaN is only ever
// the first): the slab then bounds nothing, right for a ray that runs in
// the plane of a closed box's face.
struct BoxRay {
  explicit BoxRay(const Ray& ray) {
    for (int k = 0; k < 3; ++k) {
      o[k] = hn::Set(DB(), ray.origin[k]);
      inv[k] = hn::Set(DB(), 1.0f / ray.dir[k]);
      near_row[k] = std::signbit(ray.dir[k]) ? 3 + k : k;
      far_row[k] = std::signbit(ray.dir[k]) ? k : 3 + k;
    }
  }
  hn::Vec<DB> o[3], inv[3];
  int near_row[3], far_row[3];  // LeafBvhNode::box rows
};

// The slots of `node` whose boxes the ray enters within [tmin, limit] (bit
// s: slot s), conservatively (the interval widened by 4 u a side: leaf_bvh.h),
// and where it enters each (t_near).
HWY_INLINE uint32_t HitSlots(const BoxRay& r, const LeafBvhNode& node, float tmin, float limit,
                             float* t_near) {
  const DB d;
  const hn::Vec<DB> pad = hn::Set(d, 4.0f * 0x1p-24f);
  uint32_t mask = 0;
  for (int c = 0; c < kBvhWidth; c += kBoxLanes) {
    hn::Vec<DB> tn = hn::Set(d, tmin), tf = hn::Set(d, limit);
    for (int k = 0; k < 3; ++k) {
      const hn::Vec<DB> a = hn::Mul(hn::Sub(hn::Load(d, node.box[r.near_row[k]] + c), r.o[k]), r.inv[k]);
      const hn::Vec<DB> b = hn::Mul(hn::Sub(hn::Load(d, node.box[r.far_row[k]] + c), r.o[k]), r.inv[k]);
      tn = hn::Max(a, tn);
      tf = hn::Min(b, tf);
    }
    tn = hn::Sub(tn, hn::Mul(hn::Abs(tn), pad));
    tf = hn::Add(tf, hn::Mul(hn::Abs(tf), pad));
    mask |= lane::Bits(d, hn::Le(tn, tf)) << c;
    hn::Store(tn, d, t_near + c);
  }
  return mask;
}

// One function for the same reason as traversal.cc's Traverse: the set-up,
// the stack and the best hit stay in registers.
template <bool kAnyHit>
Hit TraceLeafBvh(const KdTree& tree, const LeafBvh& bvh, const Ray& input, uint32_t origin_tri) {
  constexpr IntersectionMode kMode = IntersectionMode::kWatertight;
  Hit best;
  Ray ray = LoadRay(input);
  if (bvh.nodes.empty()) return best;
  RaySetup setup;  // the kd-tree's: the same sanitising, slack and watertight ray
  if (!SanitizeAndSetUpRay(&ray, tree.bounds, &setup)) return best;
  best.t = ray.tmax;
  const float slack = setup.slack;
  const leaf_step::LeafRay<kMode> leaf_ray(ray, setup.wray, origin_tri);
  const BoxRay box_ray(ray);
  const float* soa = tree.leaf_soa.data();
  const float* soa_end = soa + tree.leaf_soa.size();
  const LeafBvhNode* nodes = bvh.nodes.data();
  Entry stack[kBvhWidth * kMaxTraversalStack];
  int top = 0;
  uint32_t child = 0;  // the root node
  for (;;) {
    while (!(child & LeafBvhNode::kLeafBit)) {
      const LeafBvhNode& node = nodes[child];
      HWY_ALIGN float t_near[kBvhWidth];
      uint32_t mask =
          HitSlots(box_ray, node, ray.tmin, kAnyHit ? best.t : best.t + slack, t_near);
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

Hit IntersectLeafBvh(const KdTree& tree, const LeafBvh& bvh, const Ray& ray) {
  return TraceLeafBvh<false>(tree, bvh, ray, kNoHit);
}

bool OccludedLeafBvh(const KdTree& tree, const LeafBvh& bvh, const Ray& ray, uint32_t origin_tri) {
  return TraceLeafBvh<true>(tree, bvh, ray, origin_tri).hit();
}

}  // namespace kdtree
