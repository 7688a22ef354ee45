// An exact brute-force reference for many rays from one origin, made cheap by
// a conservative candidate list per direction cell.
//
// Seen from the origin O, triangle t lies inside the circular cone around the
// direction of its centroid whose half-angle is the largest angle to one of its
// vertices (a cone of half-angle < 90 degrees is convex, so it holds the whole
// triangle). Directions are binned on the 6 faces of a cube map, n x n cells
// per face; a cell's directions lie inside the cone around its centre
// direction through its corners. A ray can hit t only when the two cones meet
// (both widened by 1e-5 rad, far above the rounding of the hit point), so the
// brute-force test over that cell's candidates returns exactly what the test
// over all triangles returns (same function, same tie rule). Requires every
// triangle to subtend less than 90 degrees from O (checked).
#ifndef KDTREE_CC_ROBUST_CONE_REFERENCE_H_
#define KDTREE_CC_ROBUST_CONE_REFERENCE_H_

#include <cstdint>
#include <vector>

#include "absl/status/statusor.h"
#include "cc/geometry/intersection_mode.h"
#include "cc/geometry/ray.h"
#include "cc/geometry/triangle.h"
#include "cc/kdtree/brute_force.h"

namespace kdtree {
namespace robust {

class ConeReference {
 public:
  // Error when a triangle subtends 90 degrees or more from `origin`.
  static absl::StatusOr<ConeReference> Make(const TriangleSoup& soup, const Vec3& origin,
                                            int cells_per_face);

  // Closest hit of a ray that starts at the origin given to Make().
  Hit Intersect(const BruteForce& bf, const Ray& ray, IntersectionMode mode) const;

  // Mean candidate-list length over the cells.
  double MeanCandidates() const;

 private:
  int Cell(const Vec3& dir) const;

  Vec3 origin_;
  int n_ = 0;
  std::vector<std::vector<uint32_t>> candidates_;  // per cell
};

}  // namespace robust
}  // namespace kdtree

#endif  // KDTREE_CC_ROBUST_CONE_REFERENCE_H_
