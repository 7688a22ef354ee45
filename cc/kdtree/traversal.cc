#include "cc/kdtree/traversal.h"

#include <cassert>
#include <cmath>

#include "cc/geometry/intersect.h"
#include "cc/geometry/ray_check.h"
#include "cc/geometry/watertight.h"

namespace kdtree {

namespace {
constexpr float kPad = 4e-7f;         // about 3.4 float ulps, >= 2 gamma(3) (Ize 2013)
constexpr float kHitSlack = 64.0f * 5.9604645e-8f;  // 64 * 2^-24, see traversal.h
constexpr float kSpatialTol = 16.0f * 5.9604645e-8f;  // 16 * 2^-24, see traversal.h
}  // namespace

bool ClipRayToBox(const Ray& ray, const AABB& box, float* t0, float* t1) {
  float lo = ray.tmin, hi = ray.tmax;
  if (!(lo <= hi)) return false;
  for (int k = 0; k < 3; ++k) {
    const float o = ray.origin[k], d = ray.dir[k];
    if (!(std::isfinite(o)) || std::isnan(d)) return false;
    if (d == 0.0f) {
      if (!(o >= box.lo[k] && o <= box.hi[k])) return false;
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
    if (!(lo <= hi)) return false;
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

// The ray's largest distance, in t, to the scene box along its dominant axis:
// no triangle vertex is deeper, so it scales every triangle's t error.
float DepthScale(const Ray& ray, const AABB& box) {
  const float ax = std::fabs(ray.dir.x), ay = std::fabs(ray.dir.y), az = std::fabs(ray.dir.z);
  const int k = ax >= ay ? (ax >= az ? 0 : 2) : (ay >= az ? 1 : 2);
  const float o = ray.origin[k];
  const float depth = std::fmax(std::fabs(box.lo[k] - o), std::fabs(box.hi[k] - o));
  return depth / std::fabs(ray.dir[k]);
}

// The largest coordinate difference between the ray origin and the box.
float Reach(const Ray& ray, const AABB& box) {
  float r = 0;
  for (int k = 0; k < 3; ++k) {
    r = std::fmax(r, std::fmax(std::fabs(box.lo[k] - ray.origin[k]),
                               std::fabs(box.hi[k] - ray.origin[k])));
  }
  return r;
}

// ClipRayToBox with every slab widened by delta in space (tol[k] = delta /
// |dir[k]| in t) on top of the relative padding.
bool ClipPadded(const Ray& ray, const AABB& box, float delta, const float inv[3],
                const float tol[3], float* t0, float* t1) {
  float lo = ray.tmin, hi = ray.tmax;
  for (int k = 0; k < 3; ++k) {
    const float o = ray.origin[k];
    if (ray.dir[k] == 0.0f) {
      if (!(box.lo[k] - o <= delta && o - box.hi[k] <= delta)) return false;
      continue;
    }
    float tn = (box.lo[k] - o) * inv[k], tf = (box.hi[k] - o) * inv[k];
    if (tn > tf) std::swap(tn, tf);
    tn -= std::fabs(tn) * kPad + tol[k];
    tf += std::fabs(tf) * kPad + tol[k];
    if (tn > lo) lo = tn;
    if (tf < hi) hi = tf;
    if (!(lo <= hi)) return false;
  }
  *t0 = lo;
  *t1 = hi;
  return true;
}

template <bool kAnyHit, bool kCount, IntersectionMode kMode>
Hit Traverse(const KdTree& tree, const Ray& input, TraversalCounters* counters) {
  Hit best;
  if (kCount) ++counters->rays;
  Ray ray = input;
  if (!SanitizeRay(&ray) || tree.nodes.empty() || !tree.bounds.Valid()) return best;
  assert(kMode != IntersectionMode::kWatertight || tree.verts.size() == 3 * tree.tris.size());
  const float inv[3] = {1.0f / ray.dir.x, 1.0f / ray.dir.y, 1.0f / ray.dir.z};
  // Spatial tolerance: a triangle test may accept a point up to a few ulps of
  // the origin-to-scene distance outside the triangle; every plane is treated
  // as that thick (in t: delta / |dir[axis]|, infinite for a parallel ray).
  const float delta = kSpatialTol * Reach(ray, tree.bounds);
  const float tol[3] = {delta * std::fabs(inv[0]), delta * std::fabs(inv[1]),
                        delta * std::fabs(inv[2])};
  float t_entry, t_exit;
  if (!ClipPadded(ray, tree.bounds, delta, inv, tol, &t_entry, &t_exit)) return best;
  best.t = ray.tmax;
  const float slack = kHitSlack * DepthScale(ray, tree.bounds);
  WatertightRay wray{};
  if (kMode == IntersectionMode::kWatertight) wray = MakeWatertightRay(ray);
  const bool negative[3] = {std::signbit(ray.dir.x), std::signbit(ray.dir.y),
                            std::signbit(ray.dir.z)};
  StackEntry stack[kMaxTraversalStack];
  int top = 0;
  const KdNode* nodes = tree.nodes.data();
  const Vec3* verts = tree.verts.data();
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
      // A child is skipped only when the plane (thickened by the tolerance) is
      // clearly outside the interval.
      const float t_tol = tol[axis];
      if (t_split > t_exit + t_tol) {
        index = near;
      } else if (t_split < t_entry - t_tol) {
        index = far;
      } else if (std::fabs(t_split) < INFINITY) {
        const float ts = std::fmin(std::fmax(t_split, t_entry), t_exit);
        assert(top < kMaxTraversalStack);
        stack[top++] = StackEntry{far, ts - t_tol, t_exit};
        index = near;
        t_exit = ts + t_tol;
      } else {
        // Parallel to the plane (t_split infinite) or in it (NaN): both
        // children whole when the origin is within delta of the plane, else
        // the side the origin is on.
        const float gap = node->split - ray.origin[axis];
        if (std::fabs(gap) <= delta) {
          assert(top < kMaxTraversalStack);
          stack[top++] = StackEntry{far, t_entry, t_exit};
          index = near;
        } else {
          index = gap > 0 ? left : right;
        }
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
      bool hit;
      if (kMode == IntersectionMode::kWatertight) {
        const Vec3* p = verts + 3 * static_cast<size_t>(tri);
        hit = IntersectTriangleWatertight(wray, p[0], p[1], p[2], ray.tmin, best.t, &t, &u, &v);
      } else {
        hit = IntersectTriangle(ray, tree.tris[tri], ray.tmin, best.t, &t, &u, &v);
      }
      if (hit && Closer(t, tri, best)) {
        best.tri = tri;
        best.t = t;
        best.u = u;
        best.v = v;
        if (kAnyHit) return best;
      }
    }
    // Next node. A node that starts beyond the best hit (with the slack for
    // the rounding of triangle distances) cannot hold a nearer one or a tie.
    for (;;) {
      if (top == 0) {
        if (!best.hit()) best.t = INFINITY;
        return best;
      }
      const StackEntry& e = stack[--top];
      if (best.hit() && e.t_entry > best.t + slack) continue;
      index = e.node;
      t_entry = e.t_entry;
      t_exit = e.t_exit;
      break;
    }
  }
}

template <bool kAnyHit>
Hit Dispatch(const KdTree& tree, const Ray& ray, TraversalCounters* counters,
             IntersectionMode mode) {
  if (mode == IntersectionMode::kWatertight) {
    return counters != nullptr
               ? Traverse<kAnyHit, true, IntersectionMode::kWatertight>(tree, ray, counters)
               : Traverse<kAnyHit, false, IntersectionMode::kWatertight>(tree, ray, nullptr);
  }
  return counters != nullptr
             ? Traverse<kAnyHit, true, IntersectionMode::kFast>(tree, ray, counters)
             : Traverse<kAnyHit, false, IntersectionMode::kFast>(tree, ray, nullptr);
}

}  // namespace

Hit Intersect(const KdTree& tree, const Ray& ray) {
  return Traverse<false, false, IntersectionMode::kWatertight>(tree, ray, nullptr);
}
Hit Intersect(const KdTree& tree, const Ray& ray, TraversalCounters* counters) {
  return Traverse<false, true, IntersectionMode::kWatertight>(tree, ray, counters);
}
Hit Intersect(const KdTree& tree, const Ray& ray, IntersectionMode mode) {
  return Dispatch<false>(tree, ray, nullptr, mode);
}
Hit Intersect(const KdTree& tree, const Ray& ray, TraversalCounters* counters,
              IntersectionMode mode) {
  return Dispatch<false>(tree, ray, counters, mode);
}
bool Occluded(const KdTree& tree, const Ray& ray) {
  return Traverse<true, false, IntersectionMode::kWatertight>(tree, ray, nullptr).hit();
}
bool Occluded(const KdTree& tree, const Ray& ray, TraversalCounters* counters) {
  return Traverse<true, true, IntersectionMode::kWatertight>(tree, ray, counters).hit();
}
bool Occluded(const KdTree& tree, const Ray& ray, IntersectionMode mode) {
  return Dispatch<true>(tree, ray, nullptr, mode).hit();
}
bool Occluded(const KdTree& tree, const Ray& ray, TraversalCounters* counters,
              IntersectionMode mode) {
  return Dispatch<true>(tree, ray, counters, mode).hit();
}

}  // namespace kdtree
