#include "cc/kdtree/traversal.h"

#include <cassert>
#include <cmath>

#include "cc/geometry/intersect.h"

namespace kdtree {

namespace {
constexpr float kPad = 4e-7f;        // about 3.4 float ulps
constexpr float kSplitTol = 1e-6f;  // relative tolerance of the near/far choice
}  // namespace

bool ClipRayToBox(const Ray& ray, const AABB& box, float* t0, float* t1) {
  float lo = ray.tmin, hi = ray.tmax;
  if (!(lo <= hi)) return false;
  for (int k = 0; k < 3; ++k) {
    const float o = ray.origin[k], d = ray.dir[k];
    if (!(std::isfinite(o)) || std::isnan(d)) return false;
    if (d == 0.0f) {
      if (o < box.lo[k] || o > box.hi[k]) return false;
      continue;
    }
    const float inv = 1.0f / d;
    float tn = (box.lo[k] - o) * inv, tf = (box.hi[k] - o) * inv;
    if (tn > tf) std::swap(tn, tf);
    // Conservative padding (Ize 2013; pbrt's 1 + 2 gamma(3)): rounding of the
    // slab distances may never cut off a hit on the box boundary.
    tn -= std::fabs(tn) * kPad;
    tf += std::fabs(tf) * kPad;
    if (tn > lo) lo = tn;
    if (tf < hi) hi = tf;
    if (lo > hi) return false;
  }
  *t0 = lo;
  *t1 = hi;
  return true;
}

namespace {

struct StackEntry {
  uint32_t node;
  float t_entry, t_exit;
};

template <bool kAnyHit, bool kCount>
Hit Traverse(const KdTree& tree, const Ray& ray, TraversalCounters* counters) {
  Hit best;
  best.t = ray.tmax;
  float t_entry, t_exit;
  if (kCount) ++counters->rays;
  if (tree.nodes.empty() || !ClipRayToBox(ray, tree.bounds, &t_entry, &t_exit)) {
    best.t = INFINITY;
    return best;
  }
  const float inv[3] = {1.0f / ray.dir.x, 1.0f / ray.dir.y, 1.0f / ray.dir.z};
  const bool negative[3] = {std::signbit(ray.dir.x), std::signbit(ray.dir.y),
                            std::signbit(ray.dir.z)};
  StackEntry stack[kMaxTraversalStack];
  int top = 0;
  const KdNode* nodes = tree.nodes.data();
  uint32_t index = 0;
  for (;;) {
    const KdNode* node = &nodes[index];
    while (!node->is_leaf()) {
      if (kCount) ++counters->inner_visits;
      const int axis = node->axis();
      const float t_split = (node->split - ray.origin[axis]) * inv[axis];
      const uint32_t left = index + 1, right = node->index();
      const uint32_t near = negative[axis] ? right : left;
      const uint32_t far = negative[axis] ? left : right;
      // A child is skipped only when the plane is clearly outside the interval:
      // rounding of t_split cannot make the traversal skip a sliver of a child.
      const float tol = t_exit * kSplitTol;
      if (t_split > t_exit + tol) {
        index = near;
      } else if (t_split < t_entry - tol) {
        index = far;
      } else if (t_split == t_split) {
        assert(top < kMaxTraversalStack);
        stack[top++] = StackEntry{far, t_split, t_exit};
        index = near;
        t_exit = t_split;
      } else {  // NaN: the ray lies in the split plane
        assert(top < kMaxTraversalStack);
        stack[top++] = StackEntry{far, t_entry, t_exit};
        index = near;
      }
      node = &nodes[index];
    }
    if (kCount) ++counters->leaf_visits;
    const uint32_t count = tree.LeafCount(*node);
    const uint32_t* tris = tree.LeafBegin(*node);
    for (uint32_t i = 0; i < count; ++i) {
      if (kCount) ++counters->triangle_tests;
      const uint32_t tri = tris[i];
      float t, u, v;
      if (IntersectTriangle(ray, tree.tris[tri], ray.tmin, best.t, &t, &u, &v) &&
          Closer(t, tri, best)) {
        best.tri = tri;
        best.t = t;
        best.u = u;
        best.v = v;
        if (kAnyHit) return best;
      }
    }
    if (best.hit() && best.t <= t_exit) return best;
    // Next node; the stack is ordered along the ray, so a node entered beyond
    // the best hit ends the search.
    for (;;) {
      if (top == 0) {
        if (!best.hit()) best.t = INFINITY;
        return best;
      }
      const StackEntry& e = stack[--top];
      if (best.hit() && e.t_entry > best.t) return best;
      index = e.node;
      t_entry = e.t_entry;
      t_exit = e.t_exit;
      break;
    }
  }
}

}  // namespace

Hit Intersect(const KdTree& tree, const Ray& ray) {
  return Traverse<false, false>(tree, ray, nullptr);
}
Hit Intersect(const KdTree& tree, const Ray& ray, TraversalCounters* counters) {
  return Traverse<false, true>(tree, ray, counters);
}
bool Occluded(const KdTree& tree, const Ray& ray) {
  return Traverse<true, false>(tree, ray, nullptr).hit();
}
bool Occluded(const KdTree& tree, const Ray& ray, TraversalCounters* counters) {
  return Traverse<true, true>(tree, ray, counters).hit();
}

}  // namespace kdtree
