#include "cc/kdtree/traversal.h"

#include <cassert>
#include <cmath>

#include "cc/geometry/watertight.h"
#include "cc/kdtree/leaf_layout.h"
#include "cc/kdtree/ray_setup.h"

#include <immintrin.h>

#include "cc/kdtree/leaf_step-inl.h"

namespace kdtree {

namespace {

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
// reference, which keeps them in memory unless every call is inlined (the
// leaf step, leaf_step-inl.h's TestLeaf, shared with the BVH over the
// leaves, always is). The packet kernel's TraceLanes (ray_packet_kernel.cc)
// is one function for the same reason.
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
  // The ray in every lane of a leaf step (leaf_step-inl.h).
  const leaf_step::LeafRay<kMode> leaf_ray(ray, setup.wray, origin_tri);
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
    if (leaf_step::TestLeaf<kAnyHit, kCount, kMode>(leaf_ray, packet, soa_end, &best, counters)) {
      return best;
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
