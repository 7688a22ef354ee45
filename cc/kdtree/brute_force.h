// Brute-force reference: every triangle tested, for checking the kd-tree.
#ifndef KDTREE_CC_KDTREE_BRUTE_FORCE_H_
#define KDTREE_CC_KDTREE_BRUTE_FORCE_H_

#include <cstdint>
#include <vector>

#include "cc/geometry/intersect.h"
#include "cc/geometry/ray.h"
#include "cc/geometry/triangle.h"

namespace kdtree {

class BruteForce {
 public:
  explicit BruteForce(const TriangleSoup& soup);
  // Closest hit with ray.tmin < t <= ray.tmax; ties go to the smaller index.
  Hit Intersect(const Ray& ray) const;
  // The same over a subset of triangle indices (a candidate list that must
  // hold every triangle the ray can hit).
  Hit Intersect(const Ray& ray, const std::vector<uint32_t>& candidates) const;
  bool Occluded(const Ray& ray) const;

 private:
  std::vector<TriAccel> tris_;
};

}  // namespace kdtree

#endif  // KDTREE_CC_KDTREE_BRUTE_FORCE_H_
