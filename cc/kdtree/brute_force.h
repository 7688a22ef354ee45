// Brute-force reference: every triangle tested, for checking the kd-tree.
//
// It offers the same two intersection modes as the kd-tree traversal
// (cc/geometry/intersection_mode.h; watertight by default) and applies the
// same ray check (SanitizeRay), so comparisons are always like for like.
#ifndef KDTREE_CC_KDTREE_BRUTE_FORCE_H_
#define KDTREE_CC_KDTREE_BRUTE_FORCE_H_

#include <cstdint>
#include <vector>

#include "cc/geometry/intersect.h"
#include "cc/geometry/intersection_mode.h"
#include "cc/geometry/ray.h"
#include "cc/geometry/triangle.h"

namespace kdtree {

class BruteForce {
 public:
  explicit BruteForce(const TriangleSoup& soup);
  // Closest hit with ray.tmin < t <= ray.tmax; ties go to the smaller index.
  Hit Intersect(const Ray& ray) const { return Intersect(ray, IntersectionMode::kWatertight); }
  Hit Intersect(const Ray& ray, IntersectionMode mode) const;
  // The same over a subset of triangle indices (a candidate list that must
  // hold every triangle the ray can hit).
  Hit Intersect(const Ray& ray, const std::vector<uint32_t>& candidates) const {
    return Intersect(ray, candidates, IntersectionMode::kWatertight);
  }
  Hit Intersect(const Ray& ray, const std::vector<uint32_t>& candidates,
                IntersectionMode mode) const;
  bool Occluded(const Ray& ray) const { return Occluded(ray, IntersectionMode::kWatertight); }
  bool Occluded(const Ray& ray, IntersectionMode mode) const;

  size_t size() const { return tris_.size(); }

 private:
  template <IntersectionMode kMode, bool kAnyHit, typename Indices>
  Hit Run(const Ray& ray, const Indices& indices) const;

  std::vector<TriAccel> tris_;
  std::vector<Vec3> verts_;  // 3 per triangle, for the watertight test
};

}  // namespace kdtree

#endif  // KDTREE_CC_KDTREE_BRUTE_FORCE_H_
