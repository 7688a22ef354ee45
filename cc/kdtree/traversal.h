// Stack-based kd-tree traversal: closest hit and any hit.
//
// Hapala & Havran, "Review: Kd-tree traversal algorithms for ray tracing", CGF
// 30(1), 2011 (the report's [1]), the variant the report uses: the near child
// is the left one when the ray's direction on the split axis is positive (its
// sign bit clear, so -0 counts as negative and +0 as positive), the right one
// otherwise. With t_split the distance to the plane and [t_entry, t_exit] the
// ray's interval in the node:
//   t_split > t_exit (+ tol)    -> near child only
//   t_split < t_entry (- tol)   -> far child only
//   otherwise (ends included)   -> near child on [t_entry, t_split], the far
//                                  child on [t_split, t_exit] pushed on a stack.
// tol = 1e-6 t_exit, so float rounding of t_split never skips a child the ray
// touches. A ray lying in the plane (0 * inf = NaN) visits both children whole.
// A leaf's triangles are tested against the best hit so far; the search ends
// when the best hit lies inside the leaf's interval (t <= t_exit), which is
// the report's rule; a hit beyond t_exit is kept as the best so far and only
// confirmed once no node that could hold a nearer one is left.
//
// Per-ray counters (N_IT: triangle tests, N_TR: inner nodes visited) are a
// template parameter, so the fast path carries no counting code at all.
#ifndef KDTREE_CC_KDTREE_TRAVERSAL_H_
#define KDTREE_CC_KDTREE_TRAVERSAL_H_

#include <cstdint>

#include "cc/geometry/ray.h"
#include "cc/kdtree/tree.h"

namespace kdtree {

struct TraversalCounters {
  uint64_t triangle_tests = 0;  // N_IT summed over rays
  uint64_t inner_visits = 0;    // N_TR summed over rays
  uint64_t leaf_visits = 0;
  uint64_t rays = 0;
  void Add(const TraversalCounters& o) {
    triangle_tests += o.triangle_tests;
    inner_visits += o.inner_visits;
    leaf_visits += o.leaf_visits;
    rays += o.rays;
  }
};

// Deepest stack the traversal needs is the tree depth; Config::Validate caps
// maxDepth at 60.
inline constexpr int kMaxTraversalStack = 64;

// Closest hit with ray.tmin < t <= ray.tmax (ties: smaller triangle index).
Hit Intersect(const KdTree& tree, const Ray& ray);
Hit Intersect(const KdTree& tree, const Ray& ray, TraversalCounters* counters);

// True when any triangle is hit with ray.tmin < t <= ray.tmax (early exit).
bool Occluded(const KdTree& tree, const Ray& ray);
bool Occluded(const KdTree& tree, const Ray& ray, TraversalCounters* counters);

// The ray's interval [*t0, *t1] inside box, clipped to [ray.tmin, ray.tmax];
// false when it misses. Handles zero direction components and NaN.
bool ClipRayToBox(const Ray& ray, const AABB& box, float* t0, float* t1);

}  // namespace kdtree

#endif  // KDTREE_CC_KDTREE_TRAVERSAL_H_
